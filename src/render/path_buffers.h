#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "device_types.h"
#include "vk/buffer.h"

namespace vkdr {

class VulkanContext;

// Bytes per path slot of a list of per-path arrays (device_types.h).
#define VKDR_PATH_ARRAY_BYTES(name, Type) +gpu::Type::kElementBytes

// Structure-of-arrays path state for `capacity` paths in flight (VKDR_PATH_ARRAYS), the
// work queues, and the film. Memory depends on the capacity and the image, never on
// the path depth.
struct PathBuffers {
    PathBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount);

    uint32_t capacity;
#define VKDR_PATH_ARRAY_MEMBER(name, Type) Buffer name;
    VKDR_PATH_ARRAYS(VKDR_PATH_ARRAY_MEMBER)
    Buffer queueCounters;
    Buffer queueItems;
    Buffer film;
    Buffer countersReadback;

    // Device bytes per path slot, for sizing passes.
    static constexpr uint64_t kBytesPerPath = 0 VKDR_PATH_ARRAYS(VKDR_PATH_ARRAY_BYTES) + gpu::kQueueCount * 4;
    uint64_t deviceBytes() const;
    // Writes the buffers' addresses into `params`.
    void setAddresses(gpu::RenderParams& params) const;
};

// gpu::kGradientCopies copies (or one) of `sums` fixed-point gradient sums, `copyStride`
// sums apart (device_types.h): subgroups add to different copies, and the
// gradient_values stage reads their total as a float at `firstValue` of the adjoint's
// gradientValues.
struct GradientCopies {
    GradientCopies(const VulkanContext& context, uint32_t sumsPerCopy, uint32_t copyCount, const char* name);

    uint32_t sums;
    uint32_t copies;
    uint32_t copyStride;  // 0 for a single copy
    uint32_t firstValue = 0;
    Buffer buffer;
};

// What the adjoint pass adds: per path slot its replay state (VKDR_ADJOINT_PATH_ARRAYS),
// per pixel the target, dLoss/dI and a copy of the film, per parameter the gradient
// accumulators (VKDR_GRADIENT_ACCUMULATORS), and optionally the radiance of `keptPaths`
// rendered paths, kept for their adjoint pass.
struct AdjointBuffers {
    AdjointBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount, uint32_t mediumCount,
                   uint32_t materialCount, uint32_t punctualLightCount, uint32_t texelCount, uint32_t voxelCount,
                   uint64_t keptPaths);

    uint32_t capacity;
    VKDR_ADJOINT_PATH_ARRAYS(VKDR_PATH_ARRAY_MEMBER)
    Buffer target, imageAdjoint, lossSum, filmBaseline;  // lossSum: one fixed-point sum
#define VKDR_GRADIENT_ACCUMULATOR_MEMBER(name, field, floats, copies, items) GradientCopies name;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_GRADIENT_ACCUMULATOR_MEMBER)
#undef VKDR_GRADIENT_ACCUMULATOR_MEMBER
    Buffer gradientValues;  // the float bits of every accumulator's sums, in the order of the list
    Buffer gradientValuesReadback;  // their copy for the host, kept: a grid's is read in every iteration
    uint32_t gradientValueCount = 0;
    // The radiance and its rounding (radianceRounding) of every kept path, kKeptBytesPerPath
    // each; empty (size 0) when none are kept.
    Buffer keptRadiance;
    static constexpr uint64_t kKeptBytesPerPath = 32;

    static constexpr uint64_t kBytesPerPath = 0 VKDR_ADJOINT_PATH_ARRAYS(VKDR_PATH_ARRAY_BYTES);
    uint64_t deviceBytes() const;
    // Writes the buffers' addresses and the accumulators' copy strides into `params`.
    void setAddresses(gpu::RenderParams& params) const;
};

#undef VKDR_PATH_ARRAY_MEMBER
#undef VKDR_PATH_ARRAY_BYTES

}  // namespace vkdr
