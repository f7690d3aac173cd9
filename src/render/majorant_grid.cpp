#include "render/majorant_grid.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "device_types.h"

namespace vkdr {

// A point x in cell c (origin + k c <= x < origin + k (c + 1), k the cell edge) blends
// the voxels floor(x) and floor(x) + 1 on each axis: voxels origin + k c up to
// origin + k (c + 1) inclusive. So each voxel bounds the cell it lies in and, where it
// sits on a cell's lower face, the cell below too.
MajorantGrid buildMajorantGrid(const DensityGrid& grid) {
    constexpr int k = gpu::kMajorantCellVoxels;
    if (grid.channels != 1) {
        throw Error("grid '" + grid.name + "' has " + std::to_string(grid.channels) +
                    " values per voxel; majorants bound a grid of one");
    }
    MajorantGrid majorants;
    if (grid.voxelCount() == 0) {
        return majorants;
    }
    majorants.origin = grid.firstVoxel - 1;
    // The support spans size + 1 voxel spacings from origin.
    majorants.cells = (grid.size + 1 + (k - 1)) / k;
    majorants.maxima.assign(size_t(majorants.cells.x) * size_t(majorants.cells.y) * size_t(majorants.cells.z), 0.0f);
    auto cellsOf = [&](int offset, int axis) {
        // Cells whose closed range [k c, k (c + 1)] holds offset.
        int high = std::min(offset / k, majorants.cells[axis] - 1);
        int low = offset % k == 0 ? std::max(offset / k - 1, 0) : high;
        return glm::ivec2(low, high);
    };
    // Each layer of cells gathers from the voxel layers that touch it, so the layers fill
    // in parallel; a maximum is the same in any order.
    tbb::parallel_for(0, majorants.cells.z, [&](int j) {
        const int firstZ = std::max(k * j - 1, 0), lastZ = std::min(k * (j + 1), grid.size.z - 1);
        for (int z = firstZ; z <= lastZ; ++z) {
            const glm::ivec2 cz = cellsOf(z + 1, 2);
            if (j < cz.x || j > cz.y) {
                continue;
            }
            for (int y = 0; y < grid.size.y; ++y) {
                const glm::ivec2 cy = cellsOf(y + 1, 1);
                for (int x = 0; x < grid.size.x; ++x) {
                    const float value =
                        grid.values[(size_t(z) * size_t(grid.size.y) + size_t(y)) * size_t(grid.size.x) + size_t(x)];
                    if (value <= 0.0f) {
                        continue;
                    }
                    const glm::ivec2 cx = cellsOf(x + 1, 0);
                    for (int i = cy.x; i <= cy.y; ++i) {
                        for (int h = cx.x; h <= cx.y; ++h) {
                            float& cell = majorants.maxima[(size_t(j) * size_t(majorants.cells.y) + size_t(i)) *
                                                               size_t(majorants.cells.x) + size_t(h)];
                            cell = std::max(cell, value);
                        }
                    }
                }
            }
        }
    });
    return majorants;
}

}  // namespace vkdr
