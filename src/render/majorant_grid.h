#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "volume/density_grid.h"

namespace vkdr {

// The coarse grid that tracking walks through a density grid: cells of
// kMajorantCellVoxels^3 voxels (device_types.h), each holding the largest value the
// trilinear density takes anywhere in it, so that thin regions cost few tentative
// collisions. The cells cover the whole support of the trilinear density, which reaches
// one voxel beyond the box of voxels on every side.
struct MajorantGrid {
    glm::ivec3 origin{0};       // index coordinates of cell (0, 0, 0)'s lower corner
    glm::ivec3 cells{0};        // along x, y, z; 0 for an empty grid
    std::vector<float> maxima;  // x fastest

    float at(glm::ivec3 cell) const {
        return maxima[(size_t(cell.z) * size_t(cells.y) + size_t(cell.y)) * size_t(cells.x) + size_t(cell.x)];
    }
};

// For a grid of one value per voxel; vkdr::Error for any other.
MajorantGrid buildMajorantGrid(const DensityGrid& grid);

}  // namespace vkdr
