#pragma once
// A density grid for the shader-library tests: its voxels, a placement of index =
// voxelsPerUnit * world (voxel centres at integer index coordinates), and majorant cells
// laid out as the renderer lays them out, each bounding the trilinear density it covers
// times `looseness`.
#include <algorithm>
#include <vector>

#include "glsl_host.h"

namespace vkdr::test {
// Internal linkage, as glsl_host.h's functions and `P`: a grid binds and reads its own
// test file's copies.
namespace {

using namespace glsl;

struct HostDensityGrid {
    GpuDensityGrid grid{};
    std::vector<float> voxels;
    std::vector<float> majorants;
    float voxelsPerUnit;

    HostDensityGrid(ivec3 firstVoxel, ivec3 size, std::vector<float> values, float voxelsPerUnit_, float looseness)
        : voxels(std::move(values)), voxelsPerUnit(voxelsPerUnit_) {
        grid.worldToIndex[0] = vec4(voxelsPerUnit, 0.0f, 0.0f, 0.0f);
        grid.worldToIndex[1] = vec4(0.0f, voxelsPerUnit, 0.0f, 0.0f);
        grid.worldToIndex[2] = vec4(0.0f, 0.0f, voxelsPerUnit, 0.0f);
        grid.firstVoxel = ivec4(firstVoxel, 0);
        grid.size = ivec4(size, 0);
        // Cells of kMajorantCellVoxels from one voxel before the box; a cell bounds the
        // voxels its trilinear lookups blend, one more per axis.
        grid.majorantOrigin = grid.firstVoxel - ivec4(1, 1, 1, 0);
        const ivec3 cells = (size + 2 + kMajorantCellVoxels - 1) / kMajorantCellVoxels;
        grid.majorantCells = ivec4(cells, 1);  // one value per voxel
        for (int z = 0; z < cells.z; ++z)
            for (int y = 0; y < cells.y; ++y)
                for (int x = 0; x < cells.x; ++x) {
                    const ivec3 low = ivec3(grid.majorantOrigin) + ivec3(x, y, z) * kMajorantCellVoxels;
                    float largest = 0.0f;
                    for (int k = low.z; k <= low.z + kMajorantCellVoxels; ++k)
                        for (int j = low.y; j <= low.y + kMajorantCellVoxels; ++j)
                            for (int i = low.x; i <= low.x + kMajorantCellVoxels; ++i) largest = std::max(largest, voxel({i, j, k}));
                    majorants.push_back(looseness * largest);
                }
    }

    // The voxel's index in `voxels`, or -1 outside the box.
    int offset(ivec3 index) const {
        const ivec3 local = index - ivec3(grid.firstVoxel);
        if (any(lessThan(local, ivec3(0))) || any(greaterThanEqual(local, ivec3(grid.size)))) return -1;
        return (local.z * grid.size.y + local.y) * grid.size.x + local.x;
    }

    float voxel(ivec3 index) const {
        const int at = offset(index);
        return at < 0 ? 0.0f : voxels[size_t(at)];
    }

    // The trilinear density at world point p.
    double density(dvec3 p) const {
        const dvec3 index = p * double(voxelsPerUnit);
        const dvec3 base = floor(index), f = index - base;
        double sum = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const ivec3 c(corner & 1, (corner >> 1) & 1, corner >> 2);
            const double w = (c.x ? f.x : 1.0 - f.x) * (c.y ? f.y : 1.0 - f.y) * (c.z ? f.z : 1.0 - f.z);
            sum += w * voxel(ivec3(base) + c);
        }
        return sum;
    }

    // The majorant of the cell that holds world point p, 0 outside the cells.
    double majorant(dvec3 p) const {
        const ivec3 cell = ivec3(floor((p * double(voxelsPerUnit) - dvec3(ivec3(grid.majorantOrigin))) /
                                       double(kMajorantCellVoxels)));
        if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(grid.majorantCells)))) return 0.0;
        return majorants[size_t((cell.z * grid.majorantCells.y + cell.y) * grid.majorantCells.x + cell.x)];
    }

    void bind() const {
        P.gridValues.v = voxels.data();
        P.gridMajorants.v = majorants.data();
    }
};

}  // namespace
}  // namespace vkdr::test
