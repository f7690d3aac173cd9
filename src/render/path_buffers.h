#pragma once
#include <cstdint>
#include <vector>

#include "device_types.h"
#include "vk/buffer.h"

namespace vkdr {

class VulkanContext;

// Structure-of-arrays path state for `capacity` paths in flight, the work queues, and
// the film. Memory depends on the capacity and the image, never on the path depth.
struct PathBuffers {
    PathBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount);

    uint32_t capacity;
    Buffer rayOrigin, rayDirection, beta, radiance, misVertex, hit, pathInfo, vertexInfo;
    Buffer shadowOrigin, shadowDirection, shadowContribution;
    Buffer queueCounters;
    Buffer queueItems;
    Buffer film;
    Buffer countersReadback;

    // Device bytes per path slot, for sizing passes.
    static constexpr uint64_t kBytesPerPath = 11 * 16 + gpu::kQueueCount * 4;
    uint64_t deviceBytes() const;
};

// gpu::kGradientCopies copies of `floats` gradient accumulators, `copyStride` floats
// apart (device_types.h): subgroups add to different copies, and the host sums them.
struct GradientCopies {
    GradientCopies(const VulkanContext& context, uint32_t floatsPerCopy, const char* name);

    uint32_t floats;
    uint32_t copyStride;
    Buffer buffer;

    // Room on the host for all the copies (for downloadBuffers), and the `floats`
    // accumulators that they sum to.
    std::vector<float> roomForCopies() const;
    std::vector<float> sumOfCopies(std::span<const float> copies) const;
};

// What the adjoint pass adds: per path slot its replay state, per pixel the target,
// dLoss/dI and a copy of the film, per parameter the gradient accumulators, and
// optionally the radiance of `keptPaths` rendered paths, kept for their adjoint pass.
struct AdjointBuffers {
    AdjointBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount, uint32_t mediumCount,
                   uint32_t materialCount, uint32_t texelCount, uint64_t keptPaths);

    Buffer pendingFactor, adjointState, vertexUv, shadowScatterGradient, shadowEmissionGradient, shadowVertex;
    Buffer target, imageAdjoint, lossSum, filmBaseline;
    GradientCopies mediumGradients, baseColorGradients, emissionGradients;
    Buffer texelGradients;
    Buffer keptRadiance;  // 16 bytes per kept path; empty (size 0) when none are kept

    static constexpr uint64_t kBytesPerPath = 6 * 16;
    uint64_t deviceBytes() const;
};

}  // namespace vkdr
