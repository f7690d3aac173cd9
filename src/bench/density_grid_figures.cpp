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
    for (const SceneDensityGrid& placed : scene.densityGrids) {
        figures.voxels += placed.grid.voxelCount();
        const std::vector<float>& values = placed.grid.values;
        figures.activeVoxels +=
            uint64_t(std::count_if(values.begin(), values.end(), [](float value) { return value > 0.0f; }));
    }
    std::vector<double> buildMs;
    std::vector<MajorantGrid> majorants(scene.densityGrids.size());  // kept, so that the builds are not elided
    for (uint32_t i = 0; i < std::max(1u, iterations); ++i) {
        buildMs.push_back(millisecondsOf([&] {
            for (size_t grid = 0; grid < majorants.size(); ++grid) {
                majorants[grid] = buildMajorantGrid(scene.densityGrids[grid].grid);
            }
        }));
    }
    figures.majorantBuildMs = median(buildMs);
    return figures;
}

}  // namespace vkdr
