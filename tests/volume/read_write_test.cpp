// Density grids written as .vdb and .nvdb come back bit for bit, and what OpenVDB
// itself writes (tiles, inactive voxels, double grids) reads as the dense box it means.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>

#include "../image/scratch_directory.h"
#include "grid_files.h"
#include "volume/read_density_grid.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

void expectSameGrid(const DensityGrid& read, const DensityGrid& written) {
    EXPECT_EQ(read.name, written.name);
    EXPECT_EQ(read.firstVoxel, written.firstVoxel);
    EXPECT_EQ(read.size, written.size);
    EXPECT_EQ(read.indexToLocal, written.indexToLocal);  // exactly, every entry
    ASSERT_EQ(read.values.size(), written.values.size());
    EXPECT_EQ(std::memcmp(read.values.data(), written.values.data(), read.values.size() * sizeof(float)), 0);
}

TEST(DensityGridFiles, VdbRoundTripIsBitExact) {
    ScratchDirectory directory;
    const DensityGrid grid = patternedGrid({-5, 3, -17}, {7, 4, 9}, skewedTransform());
    writeDensityGridVdb(directory / "grid.vdb", grid);
    expectSameGrid(readDensityGrid(directory / "grid.vdb", "density"), grid);
}

TEST(DensityGridFiles, NanoVdbRoundTripIsBitExact) {
    ScratchDirectory directory;
    DensityGrid grid = patternedGrid({-40, -1, 12}, {9, 5, 6}, skewedTransform());
    grid.name = "smoke";
    writeDensityGridNanoVdb(directory / "grid.nvdb", grid);
    expectSameGrid(readDensityGrid(directory / "grid.nvdb", "smoke"), grid);
}

// NanoVDB files compressed with ZIP or Blosc read as uncompressed ones do.
TEST(DensityGridFiles, ReadsCompressedNanoVdb) {
    ScratchDirectory directory;
    const DensityGrid grid = patternedGrid({-2, 0, 5}, {6, 7, 8}, skewedTransform());
    const nanovdb::GridHandle<> handle = nanovdb::openToNanoVDB(*openVdbGrid(grid));
    for (nanovdb::io::Codec codec : {nanovdb::io::Codec::ZIP, nanovdb::io::Codec::BLOSC}) {
        const std::filesystem::path file = directory / (std::string(nanovdb::io::toStr(codec)) + ".nvdb");
        nanovdb::io::writeGrid(file.string(), handle, codec);
        expectSameGrid(readDensityGrid(file, "density"), grid);
    }
}

// Quantized NanoVDB grids (Fp4, Fp8, Fp16 and the variable-width FpN) read as floats,
// each voxel within its quantization's error of the grid written: half a quantum for
// the fixed widths, where a leaf's 2^bits - 1 quanta span at most the grid's range of
// values, and the oracle's tolerance for FpN.
TEST(DensityGridFiles, ReadsQuantizedNanoVdb) {
    ScratchDirectory directory;
    const DensityGrid grid = patternedGrid({-3, 1, 4}, {11, 9, 10}, skewedTransform());
    const float largest = *std::max_element(grid.values.begin(), grid.values.end());
    const openvdb::FloatGrid::Ptr vdb = openVdbGrid(grid);
    auto quantized = [&]<typename BuildT>(BuildT) {
        return nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, BuildT>(*vdb);
    };
    const float fpnTolerance = 1e-3f;
    nanovdb::OpenToNanoVDB<float, nanovdb::FpN> fpn;
    fpn.oracle() = nanovdb::AbsDiff(fpnTolerance);
    // Decoding rounds code * quantum + minimum to float.
    const float decoding = 4.0f * std::numeric_limits<float>::epsilon() * largest;
    auto expectWithin = [&](const std::string& name, const nanovdb::GridHandle<>& handle, float error) {
        SCOPED_TRACE(name);
        nanovdb::io::writeGrid((directory / (name + ".nvdb")).string(), handle);
        const DensityGrid read = readDensityGrid(directory / (name + ".nvdb"), "density");
        EXPECT_EQ(read.firstVoxel, grid.firstVoxel);
        EXPECT_EQ(read.size, grid.size);
        EXPECT_EQ(read.indexToLocal, grid.indexToLocal);
        ASSERT_EQ(read.values.size(), grid.values.size());
        float largestError = 0.0f;
        for (size_t i = 0; i < grid.values.size(); ++i) {
            largestError = std::max(largestError, std::abs(read.values[i] - grid.values[i]));
            if (grid.values[i] == 0.0f) {
                EXPECT_EQ(read.values[i], 0.0f) << "voxel " << i;  // inactive
            }
        }
        EXPECT_LE(largestError, error + decoding);
    };
    expectWithin("fp4", quantized(nanovdb::Fp4()), 0.5f * largest / 15.0f);
    expectWithin("fp8", quantized(nanovdb::Fp8()), 0.5f * largest / 255.0f);
    expectWithin("fp16", quantized(nanovdb::Fp16()), 0.5f * largest / 65535.0f);
    expectWithin("fpn", fpn(*vdb), fpnTolerance);
}

// Voxels of 1e-5 (a micro-CT scan in metres) are not flat, whatever OpenVDB's transforms
// make of their small determinant: a NanoVDB file of them reads with its map.
TEST(DensityGridFiles, NanoVdbOfSmallVoxelsReads) {
    ScratchDirectory directory;
    DensityGrid grid = patternedGrid({1, 2, 3}, {4, 5, 6}, glm::dmat4(1.0));
    nanovdb::GridHandle<> handle = nanovdb::openToNanoVDB(*openVdbGrid(grid));
    nanovdb::NanoGrid<float>* nano = handle.grid<float>();
    nano->data()->mMap.set(1e-5, nanovdb::Vec3d(0.5, -2.0, 3.0), 1.0);
    nanovdb::updateChecksum(*nano, nanovdb::ChecksumMode::Full);
    nanovdb::io::writeGrid((directory / "small.nvdb").string(), handle);
    grid.indexToLocal = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, -2.0, 3.0)) *
                        glm::scale(glm::dmat4(1.0), glm::dvec3(1e-5));
    expectSameGrid(readDensityGrid(directory / "small.nvdb", "density"), grid);
}

// writeDensityGrid picks the format by extension, in any case.
TEST(DensityGridFiles, WritesByExtension) {
    ScratchDirectory directory;
    const DensityGrid grid = patternedGrid({0, 0, 0}, {3, 3, 3}, glm::scale(glm::dmat4(1.0), glm::dvec3(0.5)));
    writeDensityGrid(directory / "a.VDB", grid);
    writeDensityGrid(directory / "b.nvdb", grid);
    EXPECT_EQ(fileBytes(directory / "a.VDB").substr(0, 4), std::string("\x20\x42\x44\x56", 4));  // OpenVDB's magic
    EXPECT_EQ(fileBytes(directory / "b.nvdb").substr(0, 7), "NanoVDB");
    expectSameGrid(readDensityGrid(directory / "a.VDB", "density"), grid);
    expectSameGrid(readDensityGrid(directory / "b.nvdb", "density"), grid);
}

TEST(DensityGridFiles, UnnamedGridIsWrittenAsDensity) {
    ScratchDirectory directory;
    DensityGrid grid = patternedGrid({0, 0, 0}, {2, 2, 2}, glm::dmat4(1.0));
    grid.name.clear();
    writeDensityGridVdb(directory / "grid.vdb", grid);
    EXPECT_EQ(readDensityGrid(directory / "grid.vdb", "density").values, grid.values);
}

TEST(DensityGridFiles, GridWithoutActiveVoxelsIsEmpty) {
    ScratchDirectory directory;
    DensityGrid grid;
    grid.name = "density";
    grid.indexToLocal = skewedTransform();
    writeDensityGridVdb(directory / "empty.vdb", grid);
    writeDensityGridNanoVdb(directory / "empty.nvdb", grid);
    for (const char* name : {"empty.vdb", "empty.nvdb"}) {
        const DensityGrid read = readDensityGrid(directory / name, "density");
        EXPECT_EQ(read.size, glm::ivec3(0)) << name;
        EXPECT_TRUE(read.values.empty()) << name;
        EXPECT_EQ(read.indexToLocal, grid.indexToLocal) << name;
    }
    // An all-zero box keeps its box: a fitted grid whose voxels all went to 0 is still
    // the same parameter.
    grid.size = glm::ivec3(4);
    grid.values.assign(64, 0.0f);
    writeDensityGridVdb(directory / "zeros.vdb", grid);
    const DensityGrid zeros = readDensityGrid(directory / "zeros.vdb", "density");
    EXPECT_EQ(zeros.size, grid.size);
    EXPECT_EQ(zeros.values, grid.values);
}

// An active tile (a whole 8^3 leaf of one value) is filled in voxel by voxel; an
// inactive voxel inside the box is 0 whatever value it holds.
TEST(DensityGridFiles, ActiveTilesAreFilledAndInactiveVoxelsAreZero) {
    ScratchDirectory directory;
    openvdb::FloatGrid::Ptr vdb = openVdbGrid(DensityGrid{});
    vdb->setName("density");
    vdb->tree().addTile(1, openvdb::Coord(8, 0, -8), 0.75f, true);
    vdb->tree().setValueOn(openvdb::Coord(20, 2, 3), 0.5f);
    vdb->tree().setValueOff(openvdb::Coord(18, 2, 3), 9.0f);
    ASSERT_EQ(vdb->tree().activeTileCount(), 1u);
    writeOpenVdbGrid(directory / "tile.vdb", vdb);
    const DensityGrid read = readDensityGrid(directory / "tile.vdb", "density");
    EXPECT_EQ(read.firstVoxel, glm::ivec3(8, 0, -8));
    EXPECT_EQ(read.size, glm::ivec3(13, 8, 12));
    EXPECT_EQ(read.at({8, 0, -8}), 0.75f);
    EXPECT_EQ(read.at({15, 7, -1}), 0.75f);
    EXPECT_EQ(read.at({20, 2, 3}), 0.5f);
    EXPECT_EQ(read.at({18, 2, 3}), 0.0f);
    EXPECT_EQ(read.at({16, 0, -8}), 0.0f);
    double sum = 0.0;
    for (float value : read.values) sum += value;
    EXPECT_EQ(sum, 512 * 0.75 + 0.5);
}

// A double grid is read as float: each value rounded to the nearest float.
TEST(DensityGridFiles, DoubleGridIsRoundedToFloat) {
    ScratchDirectory directory;
    openvdb::DoubleGrid::Ptr vdb = openvdb::DoubleGrid::create(0.0);
    vdb->setName("density");
    vdb->tree().setValueOn(openvdb::Coord(-3, 4, 5), 0.1);
    vdb->tree().setValueOn(openvdb::Coord(-2, 4, 5), 1.0 / 3.0);
    vdb->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    writeOpenVdbGrid(directory / "double.vdb", vdb);
    const DensityGrid read = readDensityGrid(directory / "double.vdb", "density");
    EXPECT_EQ(read.firstVoxel, glm::ivec3(-3, 4, 5));
    EXPECT_EQ(read.values, (std::vector<float>{0.1f, float(1.0 / 3.0)}));
    EXPECT_EQ(read.indexToLocal, glm::dmat4(glm::dvec4(0.25, 0, 0, 0), glm::dvec4(0, 0.25, 0, 0),
                                            glm::dvec4(0, 0, 0.25, 0), glm::dvec4(0, 0, 0, 1)));
}

// Among several grids, the one asked for.
TEST(DensityGridFiles, ReadsTheNamedGridAmongSeveral) {
    ScratchDirectory directory;
    DensityGrid smoke = patternedGrid({0, 0, 0}, {2, 3, 4}, glm::dmat4(1.0));
    smoke.name = "smoke";
    DensityGrid fire = patternedGrid({5, 5, 5}, {1, 1, 1}, glm::scale(glm::dmat4(1.0), glm::dvec3(2.0)));
    fire.name = "fire";
    openvdb::io::File((directory / "two.vdb").string()).write(openvdb::GridPtrVec{openVdbGrid(smoke), openVdbGrid(fire)});
    expectSameGrid(readDensityGrid(directory / "two.vdb", "fire"), fire);
    expectSameGrid(readDensityGrid(directory / "two.vdb", "smoke"), smoke);
}

std::filesystem::path onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream directories(path ? path : "");
    for (std::string directory; std::getline(directories, directory, ':');) {
        if (!directory.empty() && ::access((std::filesystem::path(directory) / program).c_str(), X_OK) == 0) {
            return std::filesystem::path(directory) / program;
        }
    }
    return {};
}

// OpenVDB's own tool reads what writeDensityGridVdb writes.
TEST(DensityGridFiles, VdbPrintReadsAWrittenFile) {
    const std::filesystem::path vdbPrint = onPath("vdb_print");
    if (vdbPrint.empty()) GTEST_SKIP() << "vdb_print (Debian's libopenvdb-tools) is not on PATH";
    ScratchDirectory directory;
    DensityGrid grid = patternedGrid({1, 2, 3}, {5, 6, 7}, skewedTransform());
    grid.name = "plume_density";
    writeDensityGridVdb(directory / "grid.vdb", grid);
    const std::string command = vdbPrint.string() + " -l " + (directory / "grid.vdb").string() + " > " +
                                (directory / "printed.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << fileBytes(directory / "printed.txt");
    const std::string printed = fileBytes(directory / "printed.txt");
    EXPECT_NE(printed.find("plume_density"), std::string::npos) << printed;
    EXPECT_NE(printed.find("float"), std::string::npos) << printed;
    EXPECT_NE(printed.find("fog volume"), std::string::npos) << printed;
}

}  // namespace
}  // namespace vkdr::test
