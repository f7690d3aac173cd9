// Each way a density grid file can be unusable gives one vkdr::Error naming the file
// and saying what is wrong.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>

#include <gtest/gtest.h>

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>

#include "../image/scratch_directory.h"
#include "core/proc_memory.h"
#include "expect_error.h"
#include "grid_files.h"
#include "volume/index_transform.h"
#include "volume/read_density_grid.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

void expectReadError(const std::filesystem::path& file, const std::string& gridName,
                     std::vector<std::string> parts) {
    parts.push_back(file.string());
    expectErrorMentioning([&] { readDensityGrid(file, gridName); }, parts);
}

// A .vdb file of two patterned grids of `size` voxels, named `first` and `second`.
void writeTwoGrids(const std::filesystem::path& file, const std::string& first, const std::string& second,
                   glm::ivec3 size) {
    DensityGrid grid = patternedGrid({0, 0, 0}, size, glm::dmat4(1.0));
    grid.name = first;
    openvdb::FloatGrid::Ptr firstGrid = openVdbGrid(grid);
    grid.name = second;
    openvdb::io::File(file.string()).write(openvdb::GridPtrVec{firstGrid, openVdbGrid(grid)});
}

openvdb::FloatGrid::Ptr gridWithVoxel(openvdb::Coord voxel, float value) {
    openvdb::FloatGrid::Ptr vdb = openVdbGrid(DensityGrid{});
    vdb->setName("density");
    vdb->tree().setValueOn(openvdb::Coord(0, 0, 0), 0.5f);
    vdb->tree().setValueOn(voxel, value);
    return vdb;
}

TEST(DensityGridErrors, MissingFileAndDirectory) {
    ScratchDirectory directory;
    expectReadError(directory / "missing.vdb", "density", {"no such file"});
    expectReadError(directory / "missing.nvdb", "density", {"no such file"});
    std::filesystem::create_directory(directory / "folder.vdb");
    expectReadError(directory / "folder.vdb", "density", {"is a directory"});
}

TEST(DensityGridErrors, UnknownExtension) {
    ScratchDirectory directory;
    writeBytes(directory / "grid.txt", "density");
    expectReadError(directory / "grid.txt", "density", {"unknown extension '.txt'", ".vdb or .nvdb"});
}

TEST(DensityGridErrors, NotAGridFile) {
    ScratchDirectory directory;
    writeBytes(directory / "text.vdb", "these are not the bytes of a VDB file at all");
    expectReadError(directory / "text.vdb", "density", {"not a VDB file"});
    writeBytes(directory / "text.nvdb", "these are not the bytes of a NanoVDB file at all");
    expectReadError(directory / "text.nvdb", "density", {"not a valid nvdb file"});
    writeBytes(directory / "empty.vdb", "");
    expectReadError(directory / "empty.vdb", "density", {"not a VDB file"});
    writeBytes(directory / "empty.nvdb", "");
    expectReadError(directory / "empty.nvdb", "density", {"holds no grids"});
    // Cut short after its headers.
    writeDensityGridNanoVdb(directory / "whole.nvdb", patternedGrid({0, 0, 0}, {4, 4, 4}, glm::dmat4(1.0)));
    writeBytes(directory / "cut.nvdb", fileBytes(directory / "whole.nvdb").substr(0, 1000));
    expectReadError(directory / "cut.nvdb", "density", {"damaged", "bytes on disk, beyond the file's 1000"});
}

// A file cut anywhere is refused: OpenVDB alone reads on past the end with sizes the
// failed reads left unset. The cuts: every length through the headers and the first
// bytes of the grids, then every 61st (each length costs OpenVDB's node buffers, about 2
// ms), and the last 64 bytes. The grid asked for is the second, so cuts in the first
// count too.
TEST(DensityGridErrors, VdbFileCutAnywhere) {
    ScratchDirectory directory;
    writeTwoGrids(directory / "whole.vdb", "smoke", "density", {3, 2, 2});
    const std::string whole = fileBytes(directory / "whole.vdb");
    ASSERT_EQ(readDensityGrid(directory / "whole.vdb", "density").size, glm::ivec3(3, 2, 2));
    std::vector<size_t> lengths;
    for (size_t length = 0; length < whole.size(); length += length < 1024 ? 1 : 61) lengths.push_back(length);
    for (size_t length = whole.size() - 64; length < whole.size(); ++length) lengths.push_back(length);
    for (const size_t length : lengths) {
        SCOPED_TRACE("cut at " + std::to_string(length) + " of " + std::to_string(whole.size()) + " bytes");
        writeBytes(directory / "cut.vdb", whole.substr(0, length));
        EXPECT_THROW(readDensityGrid(directory / "cut.vdb", "density"), Error);
    }
}

TEST(DensityGridErrors, NoGridOfThatNameListsTheNames) {
    ScratchDirectory directory;
    writeTwoGrids(directory / "two.vdb", "smoke", "fire", {2, 2, 2});
    expectReadError(directory / "two.vdb", "density", {"no grid named 'density'", "'smoke'", "'fire'"});
    DensityGrid smoke = patternedGrid({0, 0, 0}, {2, 2, 2}, glm::dmat4(1.0));
    smoke.name = "smoke";
    writeDensityGridNanoVdb(directory / "smoke.nvdb", smoke);
    expectReadError(directory / "smoke.nvdb", "density", {"no grid named 'density'", "'smoke'"});
    // OpenVDB numbers names only where grids share one: a lone 'density[1]' is its own name.
    smoke.name = "density[1]";
    openvdb::io::File((directory / "bracket.vdb").string()).write(openvdb::GridPtrVec{openVdbGrid(smoke)});
    expectReadError(directory / "bracket.vdb", "density", {"no grid named 'density'", "'density[1]'"});
    EXPECT_EQ(readDensityGrid(directory / "bracket.vdb", "density[1]").size, glm::ivec3(2));
    // Beside a grid of the plain name, each reads by its own.
    DensityGrid plain = patternedGrid({0, 0, 0}, {3, 3, 3}, glm::dmat4(1.0));
    plain.name = "density";
    openvdb::io::File((directory / "both.vdb").string())
        .write(openvdb::GridPtrVec{openVdbGrid(smoke), openVdbGrid(plain)});
    EXPECT_EQ(readDensityGrid(directory / "both.vdb", "density").size, glm::ivec3(3));
    EXPECT_EQ(readDensityGrid(directory / "both.vdb", "density[1]").size, glm::ivec3(2));
}

// Which of several grids of one name is meant is not known: refused, naming them as
// OpenVDB does (name[0], name[1]), by which names each still reads.
TEST(DensityGridErrors, SeveralGridsOfTheNameAreNamedOneByOne) {
    ScratchDirectory directory;
    DensityGrid first = patternedGrid({0, 0, 0}, {2, 2, 2}, glm::dmat4(1.0));
    DensityGrid second = patternedGrid({0, 0, 0}, {3, 3, 3}, glm::dmat4(1.0));
    openvdb::io::File((directory / "twice.vdb").string())
        .write(openvdb::GridPtrVec{openVdbGrid(first), openVdbGrid(second)});
    expectReadError(directory / "twice.vdb", "density",
                    {"has 2 grids named 'density'", "'density[0]', 'density[1]'"});
    EXPECT_EQ(readDensityGrid(directory / "twice.vdb", "density[1]").size, glm::ivec3(3));
    std::vector<nanovdb::GridHandle<>> handles;
    handles.push_back(nanovdb::openToNanoVDB(*openVdbGrid(first)));
    handles.push_back(nanovdb::openToNanoVDB(*openVdbGrid(second)));
    nanovdb::io::writeGrids((directory / "twice.nvdb").string(), handles);
    expectReadError(directory / "twice.nvdb", "density", {"has 2 grids named 'density'", "rename all but one"});
}

TEST(DensityGridErrors, VectorAndOtherNonScalarGrids) {
    ScratchDirectory directory;
    openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
    velocity->setName("density");
    velocity->tree().setValueOn(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1.0f, 0.0f, 0.0f));
    writeOpenVdbGrid(directory / "vector.vdb", velocity);
    expectReadError(directory / "vector.vdb", "density", {"vec3s", "not scalar densities"});

    openvdb::Int32Grid::Ptr labels = openvdb::Int32Grid::create();
    labels->setName("density");
    labels->tree().setValueOn(openvdb::Coord(1, 2, 3), 7);
    writeOpenVdbGrid(directory / "int.vdb", labels);
    expectReadError(directory / "int.vdb", "density", {"int32"});

    openvdb::BoolGrid::Ptr mask = openvdb::BoolGrid::create();
    mask->setName("density");
    mask->tree().setValueOn(openvdb::Coord(1, 2, 3), true);
    writeOpenVdbGrid(directory / "mask.vdb", mask);
    expectReadError(directory / "mask.vdb", "density", {"bool"});

    nanovdb::io::writeGrid((directory / "vector.nvdb").string(), nanovdb::openToNanoVDB(*velocity));
    expectReadError(directory / "vector.nvdb", "density", {"Vec3f", "not scalar densities"});
}

TEST(DensityGridErrors, NegativeAndNonFiniteVoxels) {
    ScratchDirectory directory;
    writeOpenVdbGrid(directory / "nan.vdb", gridWithVoxel({4, -2, 7}, std::numeric_limits<float>::quiet_NaN()));
    expectReadError(directory / "nan.vdb", "density", {"voxel (4, -2, 7)", "nan", "finite, >= 0"});
    writeOpenVdbGrid(directory / "inf.vdb", gridWithVoxel({-9, 0, 1}, std::numeric_limits<float>::infinity()));
    expectReadError(directory / "inf.vdb", "density", {"voxel (-9, 0, 1)", "inf"});
    writeOpenVdbGrid(directory / "negative.vdb", gridWithVoxel({3, 3, 3}, -0.25f));
    expectReadError(directory / "negative.vdb", "density", {"voxel (3, 3, 3)", "-0.25"});
    nanovdb::io::writeGrid((directory / "negative.nvdb").string(),
                           nanovdb::openToNanoVDB(*gridWithVoxel({3, 3, -3}, -0.25f)));
    expectReadError(directory / "negative.nvdb", "density", {"voxel (3, 3, -3)", "-0.25"});

    // A negative tile is named by its first voxel.
    openvdb::FloatGrid::Ptr tiled = gridWithVoxel({0, 0, 0}, 1.0f);
    tiled->tree().addTile(1, openvdb::Coord(16, 8, 0), -1.0f, true);
    writeOpenVdbGrid(directory / "tile.vdb", tiled);
    expectReadError(directory / "tile.vdb", "density", {"voxel (16, 8, 0)", "-1"});

    // A double beyond float's range.
    openvdb::DoubleGrid::Ptr huge = openvdb::DoubleGrid::create(0.0);
    huge->setName("density");
    huge->tree().setValueOn(openvdb::Coord(1, 1, 1), 1e300);
    writeOpenVdbGrid(directory / "huge.vdb", huge);
    expectReadError(directory / "huge.vdb", "density", {"voxel (1, 1, 1)", "1e+300", "float's range"});
}

// An emission grid's refusals name it and its values as such, not as a density's.
TEST(DensityGridErrors, AnEmissionGridIsNamedAsOne) {
    ScratchDirectory directory;
    writeOpenVdbGrid(directory / "flame.vdb", gridWithVoxel({2, 2, 2}, -1.0f));
    try {
        readEmissionGrid(directory / "flame.vdb", "density");
        ADD_FAILURE() << "a negative emission strength was read";
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind("cannot read emission grid 'density'", 0), 0u) << message;
        EXPECT_NE(message.find("voxel (2, 2, 2) holds -1; an emission strength must be finite, >= 0"),
                  std::string::npos)
            << message;
    }
}

TEST(DensityGridErrors, TransformThatIsNotAffine) {
    ScratchDirectory directory;
    openvdb::FloatGrid::Ptr vdb = gridWithVoxel({1, 1, 1}, 1.0f);
    vdb->setTransform(openvdb::math::Transform::createFrustumTransform(
        openvdb::BBoxd(openvdb::Vec3d(0.0), openvdb::Vec3d(10.0)), 0.5, 2.0, 1.0));
    writeOpenVdbGrid(directory / "frustum.vdb", vdb);
    expectReadError(directory / "frustum.vdb", "density", {"not affine", "NonlinearFrustumMap"});

    // NanoVDB keeps a frustum's taper in its map (OpenToNanoVDB refuses frustums).
    nanovdb::GridHandle<> handle = nanovdb::openToNanoVDB(*gridWithVoxel({1, 1, 1}, 1.0f));
    reinterpret_cast<nanovdb::GridData*>(handle.data())->mMap.mTaperD = 0.5;
    nanovdb::updateChecksum(*handle.grid<float>());
    nanovdb::io::writeGrid((directory / "taper.nvdb").string(), handle);
    expectReadError(directory / "taper.nvdb", "density", {"not affine", "taper 0.5"});
}

// OpenVDB refuses to make or read an affine map of determinant below 3e-15; ours also
// refuses a nearly flat voxel OpenVDB accepts, and a singular NanoVDB map.
TEST(DensityGridErrors, SingularTransform) {
    ScratchDirectory directory;
    DensityGrid grid = patternedGrid({0, 0, 0}, {2, 2, 2}, glm::dmat4(1.0));
    grid.indexToLocal[1] = glm::dvec4(1.0, 1e-9, 0.0, 0.0);  // the y axis nearly along x
    writeOpenVdbGrid(directory / "flat.vdb", openVdbGrid(grid));
    expectReadError(directory / "flat.vdb", "density", {"singular"});

    // A map OpenVDB made, turned singular in the file: a distinctive entry set to 0.
    grid.indexToLocal = glm::dmat4(1.0);
    grid.indexToLocal[1][1] = 0.123456789;
    writeOpenVdbGrid(directory / "singular.vdb", openVdbGrid(grid));
    std::string bytes = fileBytes(directory / "singular.vdb");
    const double entry = 0.123456789, zero = 0.0;
    const size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&entry), sizeof(double)));
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at, sizeof(double), std::string(reinterpret_cast<const char*>(&zero), sizeof(double)));
    writeBytes(directory / "singular.vdb", bytes);
    // OpenVDB refuses the affine map as it reads it, in its own words, which are not passed on.
    expectReadError(directory / "singular.vdb", "density", {"the transform is singular or not finite"});

    nanovdb::GridHandle<> handle = nanovdb::openToNanoVDB(*gridWithVoxel({1, 1, 1}, 1.0f));
    nanovdb::Map& map = reinterpret_cast<nanovdb::GridData*>(handle.data())->mMap;
    map.mMatD[8] = 0.0;  // z maps to nothing
    nanovdb::updateChecksum(*handle.grid<float>());
    nanovdb::io::writeGrid((directory / "singular.nvdb").string(), handle);
    expectReadError(directory / "singular.nvdb", "density", {"singular"});

    // Our writer refuses it too, before writing anything.
    grid.indexToLocal[1][1] = 0.0;
    expectErrorMentioning([&] { writeDensityGridVdb(directory / "refused.vdb", grid); }, {"refused.vdb", "singular"});
    EXPECT_FALSE(std::filesystem::exists(directory / "refused.vdb"));
}

// OpenVDB's transforms hold no voxel of volume under 3e-15, however well shaped; a file
// can still give one (a scale-and-translate map is not checked as it is read), and NaN.
// Either is named in the project's words, not OpenVDB's.
TEST(DensityGridErrors, VdbTransformOpenVdbCannotHold) {
    ScratchDirectory directory;
    openvdb::FloatGrid::Ptr vdb = gridWithVoxel({1, 1, 1}, 1.0f);
    vdb->setTransform(openvdb::math::Transform::createLinearTransform(0.125));
    vdb->transform().postTranslate(openvdb::Vec3d(0.3, 0.4, 0.5));
    ASSERT_EQ(vdb->transform().mapType(), openvdb::math::UniformScaleTranslateMap::mapType());
    writeOpenVdbGrid(directory / "grid.vdb", vdb);
    const std::string bytes = fileBytes(directory / "grid.vdb");
    auto replaced = [&](double from, double to) {
        std::string changed = bytes;
        const std::string fromBytes(reinterpret_cast<const char*>(&from), sizeof(double));
        const std::string toBytes(reinterpret_cast<const char*>(&to), sizeof(double));
        size_t count = 0;
        for (size_t at = changed.find(fromBytes); at != std::string::npos; at = changed.find(fromBytes, at + 1)) {
            changed.replace(at, sizeof(double), toBytes);
            ++count;
        }
        EXPECT_GT(count, 0u);
        return changed;
    };
    writeBytes(directory / "small.vdb", replaced(0.125, 1e-6));  // the scale and the voxel size
    expectReadError(directory / "small.vdb", "density", {"voxels are too small for OpenVDB", "1.44e-5"});
    writeBytes(directory / "nan.vdb", replaced(0.4, std::nan("")));  // the translation's y
    expectReadError(directory / "nan.vdb", "density", {"the transform has a non-finite entry"});
    for (const char* file : {"small.vdb", "nan.vdb"}) {
        try {
            readDensityGrid(directory / file, "density");
        } catch (const Error& error) {
            EXPECT_EQ(std::string(error.what()).find("ArithmeticError"), std::string::npos) << error.what();
        }
    }

    // Our writer refuses such voxels (a NanoVDB grid may have them), before writing anything.
    glm::dmat4 micrometre(1e-6);
    micrometre[3][3] = 1.0;
    DensityGrid small = patternedGrid({0, 0, 0}, {2, 2, 2}, micrometre);
    expectErrorMentioning([&] { writeDensityGridVdb(directory / "refused.vdb", small); },
                          {"refused.vdb", "voxels are too small for OpenVDB"});
    EXPECT_FALSE(std::filesystem::exists(directory / "refused.vdb"));
}

// A NanoVDB grid whose bytes do not match its checksum.
TEST(DensityGridErrors, DamagedNanoVdbGrid) {
    ScratchDirectory directory;
    writeDensityGridNanoVdb(directory / "grid.nvdb", patternedGrid({0, 0, 0}, {4, 4, 4}, glm::dmat4(1.0)));
    std::string bytes = fileBytes(directory / "grid.nvdb");
    const nanovdb::GridHandle<> handle = nanovdb::io::readGrid((directory / "grid.nvdb").string());
    const auto* grid = reinterpret_cast<const nanovdb::GridData*>(handle.data());
    const size_t nameOffset = size_t(reinterpret_cast<const char*>(grid->mGridName) - reinterpret_cast<const char*>(grid));
    bytes[bytes.size() - handle.size() + nameOffset + 1] ^= 0x20;  // the grid's own copy of its name
    writeBytes(directory / "grid.nvdb", bytes);
    expectReadError(directory / "grid.nvdb", "density", {"damaged", "checksum"});
}

// NanoVDB's reader believes the file's metadata (the grid's type and size) and the grid's
// own offsets; each, damaged, is an error, not a read past the buffer.
TEST(DensityGridErrors, NanoVdbMetadataAndOffsetsOutOfRange) {
    ScratchDirectory directory;
    writeDensityGridNanoVdb(directory / "grid.nvdb", patternedGrid({0, 0, 0}, {12, 12, 12}, glm::dmat4(1.0)));
    const std::string bytes = fileBytes(directory / "grid.nvdb");
    // The file's header, then the one grid's metadata.
    const size_t metadata = sizeof(nanovdb::io::Header);
    auto withField = [&](size_t offset, auto value) {
        std::string damaged = bytes;
        damaged.replace(offset, sizeof(value), std::string(reinterpret_cast<const char*>(&value), sizeof(value)));
        return damaged;
    };

    writeBytes(directory / "type.nvdb", withField(metadata + offsetof(nanovdb::io::MetaData, gridType), uint32_t(30)));
    expectReadError(directory / "type.nvdb", "density", {"damaged", "type is 30"});

    // NanoVDB's reader takes a grid's size in memory, and its name's, as the file gives them.
    const nanovdb::GridHandle<> handle = nanovdb::io::readGrid((directory / "grid.nvdb").string());
    const uint64_t gridSize = handle.size();
    writeBytes(directory / "short.nvdb",
               withField(metadata + offsetof(nanovdb::io::MetaData, gridSize), uint64_t(gridSize - 4096)));
    expectReadError(directory / "short.nvdb", "density",
                    {"damaged", "grid 0 takes " + std::to_string(gridSize - 4096) + " bytes in memory from " +
                                    std::to_string(gridSize) + " on disk"});
    const size_t nameSize = metadata + offsetof(nanovdb::io::MetaData, nameSize);
    writeBytes(directory / "nameless.nvdb", withField(nameSize, uint32_t(0)));
    expectReadError(directory / "nameless.nvdb", "density", {"damaged", "grid 0's name takes 0 bytes"});
    writeBytes(directory / "long_name.nvdb", withField(nameSize, uint32_t(0xfffffff0)));
    expectReadError(directory / "long_name.nvdb", "density", {"damaged", "grid 0's name takes 4294967280 bytes"});
    const size_t nameEnd = metadata + sizeof(nanovdb::io::MetaData) + std::string("density").size();
    writeBytes(directory / "unterminated.nvdb", withField(nameEnd, 'x'));
    expectReadError(directory / "unterminated.nvdb", "density", {"damaged", "grid 0's name is not terminated"});

    // The tree's offset to its root, then a lower node's to a leaf, far past the grid's
    // end, in grids without a checksum (as NanoVDB allows), which nothing else would catch.
    // The grid's bytes end the file.
    const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
    const auto* gridBytes = reinterpret_cast<const char*>(grid);
    auto inGrid = [&](const void* field) {
        return bytes.size() - gridSize + size_t(static_cast<const char*>(field) - gridBytes);
    };
    auto unchecked = [&](size_t offset, auto value) {
        std::string damaged = withField(offset, value);
        const size_t checksum = inGrid(&grid->data()->mChecksum);
        damaged.replace(checksum, sizeof(uint64_t), std::string(8, '\xff'));
        return damaged;
    };
    const auto* tree = reinterpret_cast<const nanovdb::NanoTree<float>::DataType*>(&grid->tree());
    writeBytes(directory / "root.nvdb", unchecked(inGrid(&tree->mNodeOffset[3]), uint64_t(1) << 40));
    expectReadError(directory / "root.nvdb", "density", {"damaged", "root node"});

    const auto* lower = grid->tree().getFirstNode<1>()->data();
    auto child = lower->mChildMask.beginOn();
    ASSERT_TRUE(child);
    writeBytes(directory / "leaf.nvdb", unchecked(inGrid(&lower->mTable[*child].child), int64_t(1) << 40));
    expectReadError(directory / "leaf.nvdb", "density", {"damaged", "leaf node"});

    // The grid's own header against the bytes the file gives it.
    writeBytes(directory / "grown.nvdb", unchecked(inGrid(&grid->data()->mGridSize), uint64_t(gridSize + 4096)));
    expectReadError(directory / "grown.nvdb", "density",
                    {"damaged", "its header gives it " + std::to_string(gridSize + 4096) + " bytes, the file " +
                                    std::to_string(gridSize)});
    writeBytes(directory / "tiny.nvdb", unchecked(inGrid(&grid->data()->mGridSize), uint64_t(64)));
    expectReadError(directory / "tiny.nvdb", "density", {"damaged", "its header gives it 64 bytes"});

    // NanoVDB's checksum addresses each level's nodes by the tree header's counts, and
    // a breadth-first grid's from the level's first node: both must match the tree.
    ASSERT_GT(grid->tree().nodeCount(0), 1u);
    writeBytes(directory / "count.nvdb", unchecked(inGrid(&tree->mNodeCount[0]), uint32_t(1)));
    expectReadError(directory / "count.nvdb", "density",
                    {"damaged", "counts 1 nodes at level 0, its tree holds " + std::to_string(grid->tree().nodeCount(0))});
    ASSERT_TRUE(grid->isBreadthFirst());
    writeBytes(directory / "first.nvdb", unchecked(inGrid(&tree->mNodeOffset[0]), uint64_t(gridSize - 64)));
    expectReadError(directory / "first.nvdb", "density", {"damaged", "the array of its leaf nodes lies outside"});
}

// A compressed grid's size in memory is bounded by its bytes on disk: no compression
// NanoVDB uses makes one byte more than about a thousand.
TEST(DensityGridErrors, CompressedNanoVdbAskingForExabytes) {
    ScratchDirectory directory;
    const nanovdb::GridHandle<> handle =
        nanovdb::openToNanoVDB(*openVdbGrid(patternedGrid({0, 0, 0}, {6, 6, 6}, glm::dmat4(1.0))));
    nanovdb::io::writeGrid((directory / "zip.nvdb").string(), handle, nanovdb::io::Codec::ZIP);
    std::string bytes = fileBytes(directory / "zip.nvdb");
    const uint64_t exabytes = uint64_t(1) << 62;
    bytes.replace(sizeof(nanovdb::io::Header) + offsetof(nanovdb::io::MetaData, gridSize), sizeof(exabytes),
                  std::string(reinterpret_cast<const char*>(&exabytes), sizeof(exabytes)));
    writeBytes(directory / "exabytes.nvdb", bytes);
    expectReadError(directory / "exabytes.nvdb", "density",
                    {"damaged", "grid 0 takes 4611686018427387904 bytes in memory", "more than any compression gives"});
}

// An FpN leaf's flags give its values' width, and so the bytes that follow it: a width
// NanoVDB does not define (beyond 16 bits) is damage, in a grid without a checksum.
TEST(DensityGridErrors, NanoVdbLeafOfUndefinedWidth) {
    ScratchDirectory directory;
    nanovdb::OpenToNanoVDB<float, nanovdb::FpN> fpn;
    fpn.oracle() = nanovdb::AbsDiff(1e-3f);
    nanovdb::GridHandle<> handle =
        fpn(*openVdbGrid(patternedGrid({0, 0, 0}, {12, 12, 12}, glm::dmat4(1.0))), nanovdb::StatsMode::Default,
            nanovdb::ChecksumMode::Disable, 0);
    nanovdb::NanoGrid<nanovdb::FpN>* grid = handle.grid<nanovdb::FpN>();
    ASSERT_NE(grid, nullptr);
    nanovdb::io::writeGrid((directory / "fpn.nvdb").string(), handle);
    EXPECT_NO_THROW(readDensityGrid(directory / "fpn.nvdb", "density"));
    grid->tree().getFirstNode<0>()->data()->mFlags |= uint8_t(7u << 5);  // 2^7 = 128 bits a value
    nanovdb::io::writeGrid((directory / "wide.nvdb").string(), handle);
    expectReadError(directory / "wide.nvdb", "density", {"damaged", "128 bits", "at most 16"});
}

TEST(DensityGridErrors, BoxTooLargeToHoldDensely) {
    ScratchDirectory directory;
    openvdb::FloatGrid::Ptr vdb = gridWithVoxel({2000, 2000, 2000}, 1.0f);
    writeOpenVdbGrid(directory / "far.vdb", vdb);
    expectReadError(directory / "far.vdb", "density", {"2001 x 2001 x 2001 = 8.01201e+09 voxels", "2^31 - 1"});
    // A box of 2^22 x 2^21 x 2^21 voxels, 2^64 in all, whose count wraps to 0 in 64 bits.
    openvdb::FloatGrid::Ptr wide = gridWithVoxel({-(1 << 21), -(1 << 20), -(1 << 20)}, 1.0f);
    wide->tree().setValueOn(openvdb::Coord((1 << 21) - 1, (1 << 20) - 1, (1 << 20) - 1), 1.0f);
    writeOpenVdbGrid(directory / "wide.vdb", wide);
    expectReadError(directory / "wide.vdb", "density", {"4194304 x 2097152 x 2097152 = 1.84467e+19 voxels"});
}

// A valid file whose box needs more memory than the machine has available is refused
// before the box is allocated: Linux would grant it, and end the process as it is filled.
TEST(DensityGridErrors, BoxBeyondTheMachinesMemory) {
    ScratchDirectory directory;
    openvdb::FloatGrid::Ptr vdb = gridWithVoxel({0, 0, 0}, 0.5f);
    vdb->tree().setValueOn(openvdb::Coord(1289, 1289, 1289), 0.5f);  // 2.1e9 voxels, 24 GiB as albedos
    writeOpenVdbGrid(directory / "far.vdb", vdb);
    if (availableHostBytes() >= uint64_t(1290) * 1290 * 1290 * 3 * sizeof(float)) {
        GTEST_SKIP() << "this machine has the 24 GiB available";
    }
    expectErrorMentioning([&] { readAlbedoGrid(directory / "far.vdb", "density"); },
                          {"1290 x 1290 x 1290 = 2146689000 voxels, 24.0 GiB held densely",
                           "GiB of memory this machine has available"});
}

// The process's address space, from /proc/self/status (VmSize), in bytes.
[[maybe_unused]] uint64_t addressSpaceBytes() {
    std::ifstream status("/proc/self/status");
    std::string key;
    uint64_t kilobytes = 0;
    while (status >> key) {
        if (key == "VmSize:" && status >> kilobytes) return kilobytes * 1024;
    }
    return 0;
}

// Flatness is a matter of the voxel axes' directions, not their lengths: it is judged
// alike for voxels of 1e-200 and of 1e110, whose products of lengths leave double's range.
TEST(DensityGridErrors, FlatnessDoesNotDependOnTheVoxelSize) {
    for (double size : {1e-200, 1e-5, 1.0, 1e110, 1e300}) {
        SCOPED_TRACE(size);
        glm::dmat4 upright(size);
        upright[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
        EXPECT_EQ(indexTransformProblem(upright), "");
        glm::dmat4 flat = upright;
        flat[1] = glm::dvec4(size, size * 1e-9, 0.0, 0.0);  // the y axis within 1e-9 of x
        EXPECT_NE(indexTransformProblem(flat).find("singular"), std::string::npos);
    }
}

// Two voxels far apart in a valid file: a box of 7e8 voxels (2.6 GiB of floats) where the
// process may have 1 GiB more than it holds. The reader's refusal names the box, not
// damage to the file.
TEST(DensityGridErrors, BoxTooLargeForTheProcessMemory) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#else
    if (addressSpaceBytes() == 0) GTEST_SKIP() << "/proc/self/status does not give the address space";
    ScratchDirectory directory;
    writeOpenVdbGrid(directory / "sparse.vdb", gridWithVoxel({999, 999, 699}, 1.0f));
    // The child process runs the test from its start, in a scratch directory of its own,
    // which it removes as it leaves; _exit, since threads of OpenVDB's may still run.
    const std::string style = GTEST_FLAG_GET(death_test_style);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto leave = [&](int code) {
        std::error_code ignored;
        std::filesystem::remove_all(directory.path(), ignored);
        _exit(code);
    };
    const auto readWithLimitedMemory = [&] {
        rlimit limit{};
        if (getrlimit(RLIMIT_AS, &limit) != 0) leave(3);
        // 1 GiB more than the process holds, or the hard limit where that is lower.
        limit.rlim_cur = std::min<rlim_t>(limit.rlim_max, addressSpaceBytes() + (rlim_t(1) << 30));
        if (setrlimit(RLIMIT_AS, &limit) != 0) leave(3);
        try {
            readDensityGrid(directory / "sparse.vdb", "density");
        } catch (const Error& error) {
            std::cerr << error.what() << std::endl;
            leave(2);
        }
        leave(0);
    };
    EXPECT_EXIT(readWithLimitedMemory(), testing::ExitedWithCode(2),
                "1000 x 1000 x 700 = 700000000 voxels, 2.6 GiB held densely");
    GTEST_FLAG_SET(death_test_style, style);
#endif
}

}  // namespace
}  // namespace vkdr::test
