#include "render/gpu_density_grids.h"

#include <limits>
#include <span>
#include <vector>

#include "core/error.h"
#include "device_types.h"
#include "render/majorant_grid.h"
#include "vk/context.h"

namespace vkdr {
namespace {

// Grids share the device with the path state, the BVH and the images.
constexpr uint64_t kGridShareOfDeviceMemory = 2;

// Index arithmetic is in 32 bits (a box's last voxel, the corners of its majorant cells a
// cell beyond it): coordinates are refused from 2^30 in magnitude, far from where it wraps.
// The shaders' float coordinates count from the box (deviceGrid), so they do not limit it.
constexpr int32_t kLargestIndexCoordinate = 1 << 30;

void requireFits(const VulkanContext& context, const SceneDensityGrid& placed, uint64_t valuesBefore) {
    // In 64 bits: a box that ends at int32's largest coordinate would overflow.
    const glm::i64vec3 first(placed.grid.firstVoxel);
    const glm::i64vec3 last = first + glm::i64vec3(placed.grid.size) - int64_t(1);
    if (glm::any(glm::lessThan(first, glm::i64vec3(-kLargestIndexCoordinate + 1))) ||
        glm::any(glm::greaterThan(last, glm::i64vec3(kLargestIndexCoordinate - 1)))) {
        throw Error(placed.file.string() + ": grid '" + placed.grid.name + "' has voxels at index coordinates beyond " +
                    std::to_string(kLargestIndexCoordinate - 1) +
                    " in magnitude, more than the renderer's 32-bit index arithmetic keeps exact; move its voxels "
                    "nearer the origin");
    }
    const uint64_t budget = context.deviceLocalHeapBytes() / kGridShareOfDeviceMemory;
    const uint64_t fittingVoxels = std::min<uint64_t>(budget / sizeof(float), std::numeric_limits<int32_t>::max());
    const uint64_t voxels = valuesBefore + placed.grid.values.size();
    if (voxels > fittingVoxels) {
        throw Error(placed.file.string() + ": grid '" + placed.grid.name + "' needs " +
                    std::to_string(voxels) + " values on the device (with the grids before it), more than the " +
                    std::to_string(fittingVoxels) + " that fit in half of its " +
                    std::to_string(context.deviceLocalHeapBytes() >> 20) + " MiB; crop or coarsen the grid");
    }
}

// The device's index coordinates count from the grid's box (its majorant grid's origin
// for a density grid): a float holds a point within a voxel to 2^-24 of the box's extent,
// where coordinates counted from the file's origin, which may lie millions of voxels
// away, would lose the fraction that trilinear lookups need.
gpu::GpuDensityGrid deviceGrid(const SceneDensityGrid& placed, const MajorantGrid& majorants, size_t firstValue,
                               size_t firstMajorant) {
    const glm::ivec3 origin = placed.grid.channels == 1 ? majorants.origin : placed.grid.firstVoxel;
    glm::dmat4 worldToIndex = glm::inverse(placed.indexToWorld);
    worldToIndex[3] -= glm::dvec4(glm::dvec3(origin), 0.0);
    gpu::GpuDensityGrid grid{};
    for (int row = 0; row < 3; ++row) {
        grid.worldToIndex[row] = glm::vec4(worldToIndex[0][row], worldToIndex[1][row], worldToIndex[2][row],
                                           worldToIndex[3][row]);
    }
    grid.firstVoxel = glm::ivec4(placed.grid.firstVoxel - origin, int32_t(firstValue));
    grid.size = glm::ivec4(placed.grid.size, int32_t(firstMajorant));
    grid.majorantOrigin = glm::ivec4(placed.grid.channels == 1 ? majorants.origin - origin : glm::ivec3(0), 0);
    grid.majorantCells = glm::ivec4(majorants.cells, placed.grid.channels);
    // The trilinear density reaches one voxel beyond the box on every side.
    const glm::dvec3 diagonal(placed.indexToWorld * glm::dvec4(glm::dvec3(placed.grid.size + 1), 0.0));
    const double length = glm::length(diagonal);
    grid.tracking = glm::vec4(length > 0.0 ? float(1.0 / length) : 0.0f, 0.0f, 0.0f, 0.0f);
    return grid;
}

}  // namespace

void writeDensityGrids(const VulkanContext& context, const Scene& scene, GpuDensityGrids& gpu) {
    std::vector<gpu::GpuDensityGrid> grids;
    std::vector<std::span<const std::byte>> values;  // each grid's, uploaded one after another
    size_t valueCount = 0;
    std::vector<float> maxima;
    for (const SceneDensityGrid& placed : scene.densityGrids) {
        requireFits(context, placed, valueCount);
        // Tracking walks the majorants of scalar grids only (densities; an emission grid's
        // also bound the part of a ray that gathers from it).
        const MajorantGrid majorants = placed.grid.channels == 1 ? buildMajorantGrid(placed.grid) : MajorantGrid{};
        grids.push_back(deviceGrid(placed, majorants, valueCount, maxima.size()));
        values.push_back(std::as_bytes(std::span(placed.grid.values)));
        valueCount += placed.grid.values.size();
        maxima.insert(maxima.end(), majorants.maxima.begin(), majorants.maxima.end());
    }
    overwriteBuffer(context, gpu.grids, std::as_bytes(std::span(grids)), "density grids");
    overwriteBuffer(context, gpu.values, values, "density grid values");
    overwriteBuffer(context, gpu.majorants, std::as_bytes(std::span(maxima)), "density grid majorants");
}

}  // namespace vkdr
