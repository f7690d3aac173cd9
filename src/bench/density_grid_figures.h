#pragma once
#include <cstdint>
#include <optional>

#include "scene/scene.h"

namespace vkdr {

// A scene's density grids as the benchmark reports them: every grid of the scene together.
struct DensityGridFigures {
    uint64_t voxels = 0;           // in the grids' boxes: what the device holds (docs/density-grids.md)
    uint64_t activeVoxels = 0;     // those above 0
    double majorantBuildMs = 0.0;  // buildMajorantGrid over every grid on the host, median
};

// Counts the voxels and times `iterations` majorant-grid builds (at least one); nothing
// for a scene without density grids.
std::optional<DensityGridFigures> measureDensityGrids(const Scene& scene, uint32_t iterations);

}  // namespace vkdr
