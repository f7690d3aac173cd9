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
    if (glm::any(glm::lessThan(grid.size, glm::ivec3(0))) || grid.values.size() != grid.voxelCount()) {
        throw Error(formatText("the grid's %zu values do not fill its %d x %d x %d box", grid.values.size(),
                               grid.size.x, grid.size.y, grid.size.z));
    }
    for (size_t i = 0; i < grid.values.size(); ++i) {
        if (!(grid.values[i] >= 0.0f) || !std::isfinite(grid.values[i])) {
            throw Error(formatText("value %zu is %g; a density must be finite and >= 0", i, double(grid.values[i])));
        }
    }
    const std::string problem = indexTransformProblem(grid.indexToLocal);
    if (!problem.empty()) throw Error(problem);
}

openvdb::FloatGrid::Ptr openVdbGridOf(const DensityGrid& grid) {
    initializeOpenVdb();
    openvdb::FloatGrid::Ptr vdb = openvdb::FloatGrid::create(0.0f);
    vdb->setName(grid.name.empty() ? "density" : grid.name);
    vdb->setGridClass(openvdb::GRID_FOG_VOLUME);
    vdb->setTransform(exactTransform(grid.indexToLocal));
    if (grid.voxelCount() == 0) return vdb;
    const glm::ivec3 last = grid.firstVoxel + grid.size - 1;
    const openvdb::CoordBBox box(openvdb::Coord(grid.firstVoxel.x, grid.firstVoxel.y, grid.firstVoxel.z),
                                 openvdb::Coord(last.x, last.y, last.z));
    // LayoutXYZ: x varies fastest, as in DensityGrid::values. Voxels equal to the
    // background (tolerance 0: exactly 0) stay inactive.
    const openvdb::tools::Dense<const float, openvdb::tools::LayoutXYZ> dense(box, grid.values.data());
    openvdb::tools::copyFromDense(dense, *vdb, 0.0f);
    // The box's two extreme corners are active whatever their values, so that the box
    // (and with it a fitted grid's parameter) reads back unchanged.
    vdb->tree().setValueOn(box.min());
    vdb->tree().setValueOn(box.max());
    return vdb;
}

void write(const std::filesystem::path& file, const DensityGrid& grid, const std::string& format,
           const std::function<void(std::ofstream&, const openvdb::FloatGrid::Ptr&)>& writeGrid) {
    openvdb::FloatGrid::Ptr vdb;
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

void writeDensityGridVdb(const std::filesystem::path& file, const DensityGrid& grid) {
    write(file, grid, "VDB", [](std::ofstream& out, const openvdb::FloatGrid::Ptr& vdb) {
        openvdb::io::Stream(out).write(openvdb::GridCPtrVec{vdb});
    });
}

void writeDensityGridNanoVdb(const std::filesystem::path& file, const DensityGrid& grid) {
    write(file, grid, "NanoVDB", [](std::ofstream& out, const openvdb::FloatGrid::Ptr& vdb) {
        nanovdb::io::writeGrid(out, nanovdb::openToNanoVDB(*vdb));
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
