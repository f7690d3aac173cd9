#include "volume/read_density_grid.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>  // GridValidator.h uses std::cerr without including it
#include <new>
#include <stdexcept>
#include <vector>

#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/NanoToOpenVDB.h>
#include <openvdb/io/Stream.h>

#include "core/error.h"
#include "core/format_text.h"
#include "core/proc_memory.h"
#include "image/regular_file.h"
#include "volume/grid_file_type.h"
#include "volume/index_transform.h"
#include "volume/library_complaint.h"
#include "volume/nanovdb_file_layout.h"
#include "volume/nanovdb_grid_extent.h"
#include "volume/openvdb_support.h"

namespace vkdr {
namespace {

std::string noGridNamed(const std::string& gridName, const std::vector<std::string>& names) {
    if (names.empty()) return "the file holds no grids";
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
    return "no grid named '" + gridName + "'; the file has " + list;
}

// OpenVDB lists grids of one name as name[0], name[1], ...: the grids meant by `gridName`.
std::vector<std::string> vdbGridsNamed(const std::string& gridName, const std::vector<std::string>& names) {
    std::vector<std::string> named;
    for (const std::string& name : names) {
        const bool indexed = name.size() > gridName.size() + 2 && name.compare(0, gridName.size(), gridName) == 0 &&
                             name[gridName.size()] == '[' && name.back() == ']' &&
                             name.find_first_not_of("0123456789", gridName.size() + 1) == name.size() - 1;
        if (name == gridName || indexed) named.push_back(name);
    }
    return named;
}

// Several grids of the name: which one is meant is not known.
std::string severalGridsNamed(const std::string& gridName, size_t count, const std::string& choice) {
    return "the file has " + std::to_string(count) + " grids named '" + gridName + "'; " + choice;
}

void requireUsableTransform(const glm::dmat4& indexToLocal) {
    const std::string problem = indexTransformProblem(indexToLocal);
    if (!problem.empty()) throw Error(problem);
}

// A voxel's (or a tile's) value as `quantity` (a density, an emission strength): finite,
// >= 0 and within float's range.
template <typename ValueT>
float nonNegativeOf(ValueT value, const openvdb::Coord& voxel, const char* quantity) {
    const float converted = float(value);
    if (!(value >= ValueT(0)) || !std::isfinite(converted)) {
        throw Error(formatText("voxel (%d, %d, %d) holds %g; %s must be finite, >= 0 and within float's range",
                               voxel.x(), voxel.y(), voxel.z(), double(value), quantity));
    }
    return converted;
}

// One channel of an albedo: in [0, 1].
float albedoOf(double value, const openvdb::Coord& voxel) {
    if (!(value >= 0.0 && value <= 1.0)) {
        throw Error(formatText("voxel (%d, %d, %d) holds %.9g; an albedo must be in [0, 1]", voxel.x(), voxel.y(),
                               voxel.z(), value));
    }
    return float(value);
}

// How a grid's values become the DensityGrid's: `channels` floats per value.
// A scalar grid's values as `Quantity` (its `one` value, its `many`), each finite and >= 0.
template <typename Quantity>
struct NonNegativeValues {
    static constexpr int channels = 1;
    static constexpr const char* expected = Quantity::many;
    template <typename ValueT>
    static void convert(ValueT value, const openvdb::Coord& voxel, float* out) {
        out[0] = nonNegativeOf(value, voxel, Quantity::one);
    }
};

struct Density {
    static constexpr const char* one = "a density";
    static constexpr const char* many = "scalar densities (float or double)";
};
using DensityValues = NonNegativeValues<Density>;

struct EmissionStrength {
    static constexpr const char* one = "an emission strength";
    static constexpr const char* many = "scalar emission strengths (float or double)";
};
using EmissionValues = NonNegativeValues<EmissionStrength>;

// An RGB albedo from a vector grid, or a grey one from a scalar grid.
struct AlbedoValues {
    static constexpr int channels = 3;
    static constexpr const char* expected = "albedos (float or double, scalar or 3-vector)";
    template <typename ValueT>
    static void convert(ValueT value, const openvdb::Coord& voxel, float* out) {
        if constexpr (openvdb::VecTraits<ValueT>::IsVec) {
            for (int c = 0; c < 3; ++c) out[c] = albedoOf(double(value[c]), voxel);
        } else {
            out[0] = out[1] = out[2] = albedoOf(double(value), voxel);
        }
    }
};

// The dense box of `grid`'s active voxels, active tiles filled in voxel by voxel.
template <typename Values, typename GridT>
DensityGrid denseBoxOf(const GridT& grid, const std::string& name, const glm::dmat4& indexToLocal) {
    DensityGrid dense;
    dense.name = name;
    dense.indexToLocal = indexToLocal;
    dense.channels = Values::channels;
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty()) return dense;
    const glm::i64vec3 extent = glm::i64vec3(box.max().x(), box.max().y(), box.max().z()) -
                                glm::i64vec3(box.min().x(), box.min().y(), box.min().z()) + int64_t(1);
    // An extent reaches 2^32, so the product may pass 2^64: it is checked factor by
    // factor, each partial product below kMaxDenseVoxels times 2^32.
    uint64_t count = 1;
    for (int64_t side : {extent.x, extent.y, extent.z}) {
        count *= uint64_t(side);
        if (count > kMaxDenseVoxels) {
            throw Error(formatText("its active voxels span a box of %lld x %lld x %lld = %.6g voxels, more than the "
                                   "%llu (2^31 - 1) a dense grid may hold",
                                   (long long)extent.x, (long long)extent.y, (long long)extent.z,
                                   double(extent.x) * double(extent.y) * double(extent.z),
                                   (unsigned long long)kMaxDenseVoxels));
        }
    }
    dense.firstVoxel = glm::ivec3(box.min().x(), box.min().y(), box.min().z());
    dense.size = glm::ivec3(extent);
    // Linux grants far more than it has, and would end the process when the box is filled.
    const uint64_t bytes = count * Values::channels * sizeof(float);
    if (const uint64_t available = availableHostBytes(); bytes > available) {
        throw Error(formatText("its active voxels span a box of %lld x %lld x %lld = %llu voxels, %.1f GiB held "
                               "densely, more than the %.1f GiB of memory this machine has available",
                               (long long)extent.x, (long long)extent.y, (long long)extent.z,
                               (unsigned long long)count, double(bytes) / double(1ull << 30),
                               double(available) / double(1ull << 30)));
    }
    try {
        dense.values.assign(count * size_t(Values::channels), 0.0f);
    } catch (const std::bad_alloc&) {
        // A valid sparse grid whose few voxels lie far apart: not a damaged file.
        throw Error(formatText("its active voxels span a box of %lld x %lld x %lld = %llu voxels, %.1f GiB held "
                               "densely, more memory than this process could get",
                               (long long)extent.x, (long long)extent.y, (long long)extent.z,
                               (unsigned long long)count,
                               double(count) * Values::channels * sizeof(float) / double(1ull << 30)));
    }
    const openvdb::Coord first = box.min();
    const size_t sizeX = size_t(dense.size.x), sizeY = size_t(dense.size.y);
    for (auto value = grid.cbeginValueOn(); value; ++value) {
        const openvdb::CoordBBox cells = value.getBoundingBox();  // one voxel, or all of a tile's
        float converted[Values::channels];
        Values::convert(*value, cells.min(), converted);
        if (std::all_of(converted, converted + Values::channels, [](float v) { return v == 0.0f; })) continue;
        // 64-bit counters: a tile may end at the largest int.
        for (int64_t z = cells.min().z(); z <= cells.max().z(); ++z) {
            for (int64_t y = cells.min().y(); y <= cells.max().y(); ++y) {
                const size_t row = (size_t(z - first.z()) * sizeY + size_t(y - first.y())) * sizeX;
                for (int64_t x = cells.min().x(); x <= cells.max().x(); ++x) {
                    const size_t voxel = row + size_t(x - first.x());
                    std::copy_n(converted, Values::channels,
                                dense.values.begin() + ptrdiff_t(voxel * size_t(Values::channels)));
                }
            }
        }
    }
    return dense;
}

// OpenVDB checks an affine map as it reads it, refusing (with an ArithmeticError) one that
// is not finite or whose voxels are smaller than its transforms hold: said in the
// project's words. (Other maps are checked by indexToLocalOf, which can tell which.)
Error unmappableTransform() {
    return Error("the transform is singular or not finite, or its voxels are too small for OpenVDB (OpenVDB's "
                 "transforms need a voxel's volume of at least 3e-15, voxels about 1.44e-5 across)");
}

// OpenVDB's File reads on past a file's end, using sizes and values the failed reads left
// unset: a cut file can ask for a string of gigabytes or give voxels of garbage. Reading
// the file whole through a stream that throws at its end first refuses such a file.
void requireWholeVdb(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
    try {
        openvdb::io::Stream whole(in, /*delayLoad=*/false);
    } catch (const openvdb::ArithmeticError&) {
        throw unmappableTransform();
    } catch (const std::ios_base::failure&) {
        const uintmax_t bytes = std::filesystem::file_size(file);
        // OpenVDB's magic number is 8 bytes: a shorter file is none.
        if (bytes < 8) throw Error(formatText("not a VDB file (%llu bytes)", (unsigned long long)bytes));
        throw Error(formatText("the file ends before its grids do (%llu bytes): it is truncated or damaged",
                               (unsigned long long)bytes));
    }
}

// A linear map's matrix. OpenVDB gives it as an AffineMap, whose constructor refuses a
// matrix that is not finite or whose voxels are smaller than it holds; the map's images of
// the origin and the unit axes then say which, in the project's words.
glm::dmat4 indexToLocalOf(const openvdb::math::MapBase& map) {
    try {
        return toGlm(map.getAffineMap()->getMat4());
    } catch (const openvdb::ArithmeticError&) {
        const openvdb::Vec3d origin = map.applyMap(openvdb::Vec3d(0.0));
        glm::dmat4 approximate(1.0);
        for (int axis = 0; axis < 3; ++axis) {
            openvdb::Vec3d unit(0.0);
            unit[axis] = 1.0;
            const openvdb::Vec3d image = map.applyMap(unit) - origin;
            approximate[axis] = glm::dvec4(image.x(), image.y(), image.z(), 0.0);
        }
        approximate[3] = glm::dvec4(origin.x(), origin.y(), origin.z(), 1.0);
        std::string problem = indexTransformProblem(approximate);
        if (problem.empty()) problem = openVdbMapProblem(approximate);
        if (problem.empty()) problem = "OpenVDB cannot invert the transform";
        throw Error(problem);
    }
}

template <typename Values>
DensityGrid readVdb(const std::filesystem::path& file, const std::string& gridName) {
    initializeOpenVdb();
    requireWholeVdb(file);
    openvdb::io::File vdb(file.string());
    vdb.open(false);
    std::vector<std::string> names;
    for (auto name = vdb.beginName(); name != vdb.endName(); ++name) names.push_back(*name);
    const std::vector<std::string> named = vdbGridsNamed(gridName, names);
    // OpenVDB numbers names only where several grids share one: a lone 'density[1]' is
    // that grid's own name, not a copy of 'density', and a name listed as it is, without
    // a number, belongs to one grid alone.
    const bool listedAsItIs = std::find(names.begin(), names.end(), gridName) != names.end();
    if (named.empty() || (named.size() == 1 && !listedAsItIs)) throw Error(noGridNamed(gridName, names));
    if (named.size() > 1 && !listedAsItIs) {
        throw Error(severalGridsNamed(gridName, named.size(),
                                      "name one as OpenVDB does: '" + named[0] + "', '" + named[1] + "'..."));
    }
    const openvdb::GridBase::Ptr grid = vdb.readGrid(gridName);
    vdb.close();
    const bool isFloat = grid->isType<openvdb::FloatGrid>(), isDouble = grid->isType<openvdb::DoubleGrid>();
    const bool isVector =
        Values::channels == 3 && (grid->isType<openvdb::Vec3SGrid>() || grid->isType<openvdb::Vec3DGrid>());
    if (!isFloat && !isDouble && !isVector) {
        throw Error("the grid holds " + grid->valueType() + " values, not " + Values::expected);
    }
    const openvdb::math::Transform& transform = grid->transform();
    if (!transform.isLinear()) throw Error("the transform is not affine (it is a " + transform.mapType() + ")");
    const glm::dmat4 indexToLocal = indexToLocalOf(*transform.baseMap());
    requireUsableTransform(indexToLocal);
    if (isFloat) {
        return denseBoxOf<Values>(*openvdb::gridConstPtrCast<openvdb::FloatGrid>(grid), gridName, indexToLocal);
    }
    if constexpr (Values::channels == 3) {
        if (grid->isType<openvdb::Vec3SGrid>()) {
            return denseBoxOf<Values>(*openvdb::gridConstPtrCast<openvdb::Vec3SGrid>(grid), gridName, indexToLocal);
        }
        if (grid->isType<openvdb::Vec3DGrid>()) {
            return denseBoxOf<Values>(*openvdb::gridConstPtrCast<openvdb::Vec3DGrid>(grid), gridName, indexToLocal);
        }
    }
    // The type checks above leave only a double grid.
    return denseBoxOf<Values>(*openvdb::gridConstPtrCast<openvdb::DoubleGrid>(grid), gridName, indexToLocal);
}

// NanoVDB keeps the 3x3 part of the map transposed against OpenVDB's (Map::set): it maps
// column vectors, as glm does. NanoToOpenVDB copies it without transposing, so the
// converted grid's own transform is not used.
glm::dmat4 indexToLocalOf(const nanovdb::Map& map) {
    if (map.mTaperD != 1.0) throw Error(formatText("the transform is not affine (a frustum of taper %g)", map.mTaperD));
    glm::dmat4 indexToLocal(1.0);
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) indexToLocal[column][row] = map.mMatD[3 * row + column];
        indexToLocal[3][row] = map.mVecD[row];
    }
    return indexToLocal;
}

template <typename Values, typename ValueT>
DensityGrid denseBoxOfNanoGrid(nanovdb::NanoGrid<ValueT>* grid, const std::string& gridName) {
    if (grid == nullptr) throw Error("the grid's header and its contents disagree on its value type");
    requireNodesWithinGrid(*grid);
    const std::string damage = nanovdb::GridValidator<ValueT>::check(*grid, true);
    if (!damage.empty()) throw Error("the grid is damaged (" + damage + ")");
    const glm::dmat4 indexToLocal = indexToLocalOf(grid->map());
    requireUsableTransform(indexToLocal);
    // The conversion makes an OpenVDB transform of the map, which refuses voxels smaller
    // than about 1.4e-5 that the rule above accepts; only the voxels are used from it.
    grid->data()->mMap.set(1.0, nanovdb::Vec3d(0.0), 1.0);
    return denseBoxOf<Values>(*nanovdb::nanoToOpenVDB(*grid), gridName, indexToLocal);
}

template <typename Values>
DensityGrid readNanoVdb(const std::filesystem::path& file, const std::string& gridName) {
    initializeOpenVdb();
    requireSoundNanoVdbLayout(file);
    const std::vector<nanovdb::io::GridMetaData> grids = nanovdb::io::readGridMetaData(file.string());
    std::vector<std::string> names;
    const nanovdb::io::GridMetaData* found = nullptr;
    size_t sameName = 0;
    for (const nanovdb::io::GridMetaData& grid : grids) {
        names.push_back(grid.gridName);
        if (grid.gridName == gridName && sameName++ == 0) found = &grid;
    }
    if (found == nullptr) throw Error(noGridNamed(gridName, names));
    if (sameName > 1) throw Error(severalGridsNamed(gridName, sameName, "rename all but one"));
    const nanovdb::GridType type = found->gridType;
    if (uint32_t(type) >= uint32_t(nanovdb::GridType::End)) {
        throw Error(formatText("the grid is damaged (its type is %u, which NanoVDB does not define)", unsigned(type)));
    }
    const bool isVector = Values::channels == 3 && type == nanovdb::GridType::Vec3f;
    const bool isQuantized = type == nanovdb::GridType::Fp4 || type == nanovdb::GridType::Fp8 ||
                             type == nanovdb::GridType::Fp16 || type == nanovdb::GridType::FpN;
    if (type != nanovdb::GridType::Float && type != nanovdb::GridType::Double && !isVector && !isQuantized) {
        throw Error(std::string("the grid holds ") + nanovdb::toStr(type) + " values, not " + Values::expected);
    }
    nanovdb::GridHandle<nanovdb::HostBuffer> handle = nanovdb::io::readGrid(file.string(), gridName);
    requireGridWithinBuffer(handle.data(), handle.size());
    switch (type) {
    case nanovdb::GridType::Float: return denseBoxOfNanoGrid<Values>(handle.grid<float>(), gridName);
    case nanovdb::GridType::Fp4: return denseBoxOfNanoGrid<Values>(handle.grid<nanovdb::Fp4>(), gridName);
    case nanovdb::GridType::Fp8: return denseBoxOfNanoGrid<Values>(handle.grid<nanovdb::Fp8>(), gridName);
    case nanovdb::GridType::Fp16: return denseBoxOfNanoGrid<Values>(handle.grid<nanovdb::Fp16>(), gridName);
    case nanovdb::GridType::FpN: return denseBoxOfNanoGrid<Values>(handle.grid<nanovdb::FpN>(), gridName);
    case nanovdb::GridType::Vec3f:
        if constexpr (Values::channels == 3) return denseBoxOfNanoGrid<Values>(handle.grid<nanovdb::Vec3f>(), gridName);
        break;
    default: break;
    }
    // The type checks above leave only a double grid.
    return denseBoxOfNanoGrid<Values>(handle.grid<double>(), gridName);
}

void requireReadableFile(const std::filesystem::path& file) {
    const std::string reason = notRegularFileReason(file);
    if (!reason.empty()) throw Error(reason);
    std::ifstream probe(file, std::ios::binary);
    if (!probe) throw Error(std::strerror(errno));
}

template <typename Values>
DensityGrid readGrid(const std::filesystem::path& file, const std::string& gridName, const char* kind) {
    const std::string context =
        std::string("cannot read ") + kind + " grid '" + gridName + "' from '" + file.string() + "': ";
    const std::optional<GridFileType> type = gridFileTypeOf(file);
    if (!type) {
        throw Error(context + "unknown extension '" + file.extension().string() + "' (expected .vdb or .nvdb)");
    }
    // A damaged file can make OpenVDB's or NanoVDB's reader ask for any amount of memory,
    // or for more than a vector can hold.
    auto askedForTooMuch = [&] {
        std::error_code ignored;
        return Error(context + formatText("reading it asked for more memory than this machine has; the file (%llu "
                                          "bytes) may be truncated or damaged",
                                          (unsigned long long)std::filesystem::file_size(file, ignored)));
    };
    try {
        requireReadableFile(file);
        return *type == GridFileType::Vdb ? readVdb<Values>(file, gridName) : readNanoVdb<Values>(file, gridName);
    } catch (const std::bad_alloc&) {
        throw askedForTooMuch();
    } catch (const std::length_error&) {
        throw askedForTooMuch();
    } catch (const Error& error) {
        throw Error(context + error.what());
    } catch (const std::exception& error) {
        // OpenVDB's and NanoVDB's own complaints about the file (not a VDB file, truncated, ...).
        throw Error(context + boundedComplaint(error.what()));
    }
}

}  // namespace

DensityGrid readDensityGrid(const std::filesystem::path& file, const std::string& gridName) {
    return readGrid<DensityValues>(file, gridName, "density");
}

DensityGrid readEmissionGrid(const std::filesystem::path& file, const std::string& gridName) {
    return readGrid<EmissionValues>(file, gridName, "emission");
}

DensityGrid readAlbedoGrid(const std::filesystem::path& file, const std::string& gridName) {
    return readGrid<AlbedoValues>(file, gridName, "albedo");
}

}  // namespace vkdr
