#include "volume/write_density_grid.h"

#include <cmath>
#include <new>

#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Dense.h>

#include "core/error.h"
#include "core/format_text.h"
#include "image/atomic_write.h"
#include "volume/grid_file_type.h"
#include "volume/index_transform.h"
#include "volume/openvdb_support.h"

namespace vkdr {
namespace {

void requireWritable(const DensityGrid& grid) {
    if (glm::any(glm::lessThan(grid.size, glm::ivec3(0))) || (grid.channels != 1 && grid.channels != 3) ||
        grid.values.size() != grid.voxelCount() * size_t(grid.channels)) {
        throw Error(formatText("the grid's %zu values do not fill its %d x %d x %d box with %d channels",
                               grid.values.size(), grid.size.x, grid.size.y, grid.size.z, grid.channels));
    }
    for (size_t i = 0; i < grid.values.size(); ++i) {
        if (!(grid.values[i] >= 0.0f) || !std::isfinite(grid.values[i])) {
            throw Error(formatText("value %zu is %g; a grid's values must be finite and >= 0", i,
                                   double(grid.values[i])));
        }
    }
    const std::string problem = gridTransformWriteProblem(grid.indexToLocal);
    if (!problem.empty()) throw Error(problem);
}

// The grid as an OpenVDB grid of ValueT (float, or Vec3s for 3 channels).
template <typename GridT>
typename GridT::Ptr openVdbGridOf(const DensityGrid& grid) {
    using ValueT = typename GridT::ValueType;
    initializeOpenVdb();
    typename GridT::Ptr vdb = GridT::create(ValueT(0.0f));
    vdb->setName(grid.name.empty() ? "density" : grid.name);
    // A fog volume is a scalar grid (NanoVDB refuses the class on vectors).
    vdb->setGridClass(grid.channels == 1 ? openvdb::GRID_FOG_VOLUME : openvdb::GRID_UNKNOWN);
    vdb->setTransform(exactTransform(grid.indexToLocal));
    if (grid.voxelCount() == 0) return vdb;
    const glm::ivec3 last = grid.firstVoxel + grid.size - 1;
    const openvdb::CoordBBox box(openvdb::Coord(grid.firstVoxel.x, grid.firstVoxel.y, grid.firstVoxel.z),
                                 openvdb::Coord(last.x, last.y, last.z));
    // LayoutXYZ: x varies fastest, as in DensityGrid::values (whose channels are a Vec3s's
    // components). Voxels equal to the background (tolerance 0: exactly 0) stay inactive.
    const openvdb::tools::Dense<const ValueT, openvdb::tools::LayoutXYZ> dense(
        box, reinterpret_cast<const ValueT*>(grid.values.data()));
    openvdb::tools::copyFromDense(dense, *vdb, ValueT(0.0f));
    // The box's two extreme corners are active whatever their values, so that the box
    // (and with it a fitted grid's parameter) reads back unchanged.
    vdb->tree().setValueOn(box.min());
    vdb->tree().setValueOn(box.max());
    return vdb;
}

static_assert(sizeof(openvdb::Vec3s) == 3 * sizeof(float));

openvdb::GridBase::Ptr openVdbGridOf(const DensityGrid& grid) {
    if (grid.channels == 3) return openVdbGridOf<openvdb::Vec3SGrid>(grid);
    return openVdbGridOf<openvdb::FloatGrid>(grid);
}

void write(const std::filesystem::path& file, const DensityGrid& grid, const std::string& format,
           const std::function<void(std::ofstream&, const openvdb::GridBase::Ptr&)>& writeGrid) {
    openvdb::GridBase::Ptr vdb;
    try {
        requireWritable(grid);
        vdb = openVdbGridOf(grid);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& error) {
        throw Error("cannot write " + format + " '" + file.string() + "': " + error.what());
    }
    writeAtomically(file, [&](std::ofstream& out) { writeGrid(out, vdb); });
}

}  // namespace

std::string gridTransformWriteProblem(const glm::dmat4& indexToLocal) {
    const std::string problem = indexTransformProblem(indexToLocal);
    return problem.empty() ? openVdbMapProblem(indexToLocal) : problem;
}

void writeDensityGridVdb(const std::filesystem::path& file, const DensityGrid& grid) {
    write(file, grid, "VDB", [](std::ofstream& out, const openvdb::GridBase::Ptr& vdb) {
        openvdb::io::Stream(out).write(openvdb::GridCPtrVec{vdb});
    });
}

void writeDensityGridNanoVdb(const std::filesystem::path& file, const DensityGrid& grid) {
    write(file, grid, "NanoVDB", [](std::ofstream& out, const openvdb::GridBase::Ptr& vdb) {
        if (vdb->isType<openvdb::Vec3SGrid>()) {
            nanovdb::io::writeGrid(out, nanovdb::openToNanoVDB(*openvdb::gridPtrCast<openvdb::Vec3SGrid>(vdb)));
        } else {
            nanovdb::io::writeGrid(out, nanovdb::openToNanoVDB(*openvdb::gridPtrCast<openvdb::FloatGrid>(vdb)));
        }
    });
}

void writeDensityGrid(const std::filesystem::path& file, const DensityGrid& grid) {
    const std::optional<GridFileType> type = gridFileTypeOf(file);
    if (!type) {
        throw Error("cannot write density grid '" + file.string() + "': unknown extension '" +
                    file.extension().string() + "' (expected .vdb or .nvdb)");
    }
    if (*type == GridFileType::Vdb) {
        writeDensityGridVdb(file, grid);
    } else {
        writeDensityGridNanoVdb(file, grid);
    }
}

}  // namespace vkdr
