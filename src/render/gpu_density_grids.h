#pragma once
#include "scene/scene.h"
#include "vk/buffer.h"

namespace vkdr {

class VulkanContext;

// The scene's density grids as the stages read them (device_types.h, GpuDensityGrid):
// each grid's placement, its voxels and its majorant cells.
struct GpuDensityGrids {
    Buffer grids;
    Buffer values;
    Buffer majorants;
};

// Writes the scene's grids, their placements and majorant cells (rebuilt from the
// voxels) into `gpu`, in place where the sizes are unchanged. Throws vkdr::Error naming
// the grid's file when the grids need more than half the device's memory, saying how
// many voxels fit.
void writeDensityGrids(const VulkanContext& context, const Scene& scene, GpuDensityGrids& gpu);

}  // namespace vkdr
