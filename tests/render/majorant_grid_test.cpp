// The majorant cells bound the trilinear density everywhere in them, tightly, on random
// grids: sizes that are and are not multiples of the cell edge, boxes off the origin,
// many zero voxels.
#include <gtest/gtest.h>

#include <random>

#include "device_types.h"
#include "render/majorant_grid.h"

namespace vkdr::test {
namespace {

// Trilinear interpolation between voxel centres, written independently of the shaders.
double trilinear(const DensityGrid& grid, glm::dvec3 p) {
    const glm::dvec3 base = glm::floor(p);
    const glm::ivec3 v(base);
    const glm::dvec3 w = p - base;
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        glm::ivec3 offset(corner & 1, (corner >> 1) & 1, corner >> 2);
        double weight = (offset.x ? w.x : 1.0 - w.x) * (offset.y ? w.y : 1.0 - w.y) * (offset.z ? w.z : 1.0 - w.z);
        sum += weight * grid.at(v + offset);
    }
    return sum;
}

DensityGrid randomGrid(std::mt19937& random) {
    std::uniform_int_distribution<int> size(1, 21), first(-12, 12);
    std::uniform_real_distribution<float> value(0.0f, 5.0f), unit(0.0f, 1.0f);
    DensityGrid grid;
    grid.size = glm::ivec3(size(random), size(random), size(random));
    grid.firstVoxel = glm::ivec3(first(random), first(random), first(random));
    for (size_t i = 0; i < grid.voxelCount(); ++i) {
        grid.values.push_back(unit(random) < 0.6f ? 0.0f : value(random));
    }
    return grid;
}

TEST(MajorantGridTest, BoundsTheTrilinearDensityTightly) {
    constexpr int k = gpu::kMajorantCellVoxels;
    std::mt19937 random(17);
    for (int trial = 0; trial < 40; ++trial) {
        const DensityGrid grid = randomGrid(random);
        const MajorantGrid majorants = buildMajorantGrid(grid);
        SCOPED_TRACE("grid " + std::to_string(trial));
        ASSERT_EQ(majorants.origin, grid.firstVoxel - 1);
        // The cells cover the support: the box of voxels and one voxel spacing around it.
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(majorants.origin + k * majorants.cells, grid.firstVoxel + grid.size)));
        const glm::dvec3 lo(majorants.origin), hi(majorants.origin + k * majorants.cells);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (int i = 0; i < 4000; ++i) {
            // Points inside the cells and up to two voxels outside them.
            glm::dvec3 p = lo - 2.0 + (hi - lo + 4.0) * glm::dvec3(unit(random), unit(random), unit(random));
            glm::ivec3 cell(glm::floor((p - lo) / double(k)));
            const double density = trilinear(grid, p);
            if (glm::any(glm::lessThan(cell, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(cell, majorants.cells))) {
                ASSERT_EQ(density, 0.0) << "outside the cells at " << p.x << ", " << p.y << ", " << p.z;
                continue;
            }
            ASSERT_LE(density, double(majorants.at(cell)) * (1.0 + 1e-6))
                << "at " << p.x << ", " << p.y << ", " << p.z;
        }
        // Tight: each cell holds the largest voxel a point in it can blend, no more.
        for (int z = 0; z < majorants.cells.z; ++z) {
            for (int y = 0; y < majorants.cells.y; ++y) {
                for (int x = 0; x < majorants.cells.x; ++x) {
                    glm::ivec3 cell(x, y, z);
                    float largest = 0.0f;
                    glm::ivec3 first = majorants.origin + k * cell;
                    for (int dz = 0; dz <= k; ++dz) {
                        for (int dy = 0; dy <= k; ++dy) {
                            for (int dx = 0; dx <= k; ++dx) {
                                largest = std::max(largest, grid.at(first + glm::ivec3(dx, dy, dz)));
                            }
                        }
                    }
                    ASSERT_EQ(majorants.at(cell), largest) << "cell " << x << ", " << y << ", " << z;
                }
            }
        }
    }
}

TEST(MajorantGridTest, EmptyGridHasNoCells) {
    DensityGrid grid;
    EXPECT_EQ(buildMajorantGrid(grid).cells, glm::ivec3(0));
}

}  // namespace
}  // namespace vkdr::test
