#include "bench/density_grid_figures.h"

#include <algorithm>
#include <vector>

#include "bench/median.h"
#include "core/milliseconds_of.h"
#include "render/majorant_grid.h"

namespace vkdr {

std::optional<DensityGridFigures> measureDensityGrids(const Scene& scene, uint32_t iterations) {
    if (scene.densityGrids.empty()) {
        return std::nullopt;
    }
    DensityGridFigures figures;
    // The renderer builds majorants for the grids of one value per voxel (densities and
    // emission strengths); an albedo grid's voxels count once each.
    std::vector<const DensityGrid*> scalar;
    for (const SceneDensityGrid& placed : scene.densityGrids) {
        const DensityGrid& grid = placed.grid;
        figures.voxels += grid.voxelCount();
        const size_t channels = size_t(grid.channels);
        for (size_t voxel = 0; voxel < grid.voxelCount(); ++voxel) {
            const auto first = grid.values.begin() + ptrdiff_t(voxel * channels);
            figures.activeVoxels += std::any_of(first, first + ptrdiff_t(channels), [](float v) { return v > 0.0f; });
        }
        if (grid.channels == 1) scalar.push_back(&grid);
    }
    std::vector<double> buildMs;
    std::vector<MajorantGrid> majorants(scalar.size());  // kept, so that the builds are not elided
    for (uint32_t i = 0; i < std::max(1u, iterations); ++i) {
        buildMs.push_back(millisecondsOf([&] {
            for (size_t grid = 0; grid < majorants.size(); ++grid) {
                majorants[grid] = buildMajorantGrid(*scalar[grid]);
            }
        }));
    }
    figures.majorantBuildMs = median(buildMs);
    return figures;
}

}  // namespace vkdr
