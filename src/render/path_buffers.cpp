#include "render/path_buffers.h"

#include <algorithm>

#include "core/error.h"
#include "vk/context.h"

namespace vkdr {
namespace {

template <typename Element>
Buffer perPath(const VulkanContext& context, uint32_t capacity, const char* name) {
    return Buffer(context, uint64_t(capacity) * Element::kElementBytes, MemoryUse::Device, name);
}

constexpr uint64_t kBytesPerSum = gpu::kFixedPointWordsPerSum * 8;

uint32_t copyStrideOf(uint32_t sums, uint32_t copyCount) {
    if (copyCount == 1) {
        return 0;
    }
    return (sums + gpu::kGradientCopyAlignment - 1) / gpu::kGradientCopyAlignment * gpu::kGradientCopyAlignment;
}

// An accumulator's copies, with room for `items` of what it accumulates (at least one).
// The shaders index its words with 32-bit integers, which bounds the items.
GradientCopies gradientCopies(const VulkanContext& context, gpu::GradientAccumulator accumulator, uint32_t items,
                              const char* name) {
    const gpu::GradientAccumulatorLayout layout = gpu::layoutOf(accumulator);
    const uint64_t maxSums = UINT32_MAX / (uint64_t(layout.copies) * gpu::kFixedPointWordsPerSum) -
                             gpu::kGradientCopyAlignment;
    const uint64_t sums = std::max<uint64_t>(1, items) * layout.sumsPerItem;
    if (sums > maxSums) {
        throw Error(std::string(name) + ": " + std::to_string(items) + " items to differentiate, more than the " +
                    std::to_string(maxSums / layout.sumsPerItem) +
                    " the adjoint pass can address; differentiate fewer or smaller textures or grids");
    }
    return GradientCopies(context, uint32_t(sums), layout.copies, name);
}

}  // namespace

GradientCopies::GradientCopies(const VulkanContext& context, uint32_t sumsPerCopy, uint32_t copyCount,
                               const char* name)
    : sums(sumsPerCopy),
      copies(copyCount),
      copyStride(copyStrideOf(sumsPerCopy, copyCount)),
      buffer(context, (uint64_t(copyCount - 1) * copyStride + sumsPerCopy) * kBytesPerSum, MemoryUse::Device,
             name) {}

#define VKDR_ALLOCATE_PATH_ARRAY(name, Type) name(perPath<gpu::Type>(context, capacity, #name)),

PathBuffers::PathBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount)
    : capacity(capacity),
      VKDR_PATH_ARRAYS(VKDR_ALLOCATE_PATH_ARRAY)
      queueCounters(context, sizeof(gpu::QueueCountersData), MemoryUse::Device, "queue counters"),
      queueItems(context, uint64_t(capacity) * gpu::kQueueCount * 4, MemoryUse::Device, "queue items"),
      film(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "film"),
      countersReadback(context, sizeof(gpu::QueueCountersData), MemoryUse::Readback, "queue counters readback") {}

uint64_t PathBuffers::deviceBytes() const {
    return uint64_t(capacity) * kBytesPerPath + film.size() + queueCounters.size();
}

#define VKDR_SET_ADDRESS(name, ...) params.name = name.address();

void PathBuffers::setAddresses(gpu::RenderParams& params) const {
    VKDR_PATH_ARRAYS(VKDR_SET_ADDRESS)
    params.queueCounters = queueCounters.address();
    params.queueItems = queueItems.address();
    params.film = film.address();
    params.pathCapacity = capacity;
}

#define VKDR_ALLOCATE_ACCUMULATOR(name, field, floats, copies, items) \
    name(gradientCopies(context, gpu::GradientAccumulator::name, items, #name)),

AdjointBuffers::AdjointBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount,
                               uint32_t mediumCount, uint32_t materialCount, uint32_t punctualLightCount,
                               uint32_t texelCount, uint32_t voxelCount,
                               uint64_t keptPaths)
    : capacity(capacity),
      VKDR_ADJOINT_PATH_ARRAYS(VKDR_ALLOCATE_PATH_ARRAY)
      target(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "target"),
      imageAdjoint(context, uint64_t(pixelCount) * 32, MemoryUse::Device, "image adjoint"),  // two halves
      lossSum(context, kBytesPerSum, MemoryUse::Device, "loss sum"),
      filmBaseline(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "film baseline"),
      VKDR_GRADIENT_ACCUMULATORS(VKDR_ALLOCATE_ACCUMULATOR)
      keptRadiance() {
#define VKDR_PLACE_VALUES(name, ...)      \
    name.firstValue = gradientValueCount; \
    gradientValueCount += name.sums;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_PLACE_VALUES)
#undef VKDR_PLACE_VALUES
    gradientValues = Buffer(context, uint64_t(gradientValueCount) * 4, MemoryUse::Device, "gradient values");
    gradientValuesReadback =
        Buffer(context, uint64_t(gradientValueCount) * 4, MemoryUse::Readback, "gradient values (readback)");
    if (keptPaths > 0) {
        keptRadiance = Buffer(context, keptPaths * kKeptBytesPerPath, MemoryUse::Device, "kept radiance");
    }
}

#define VKDR_ACCUMULATOR_BYTES(name, ...) +name.buffer.size()

uint64_t AdjointBuffers::deviceBytes() const {
    return uint64_t(capacity) * kBytesPerPath + target.size() + imageAdjoint.size() +
           filmBaseline.size() VKDR_GRADIENT_ACCUMULATORS(VKDR_ACCUMULATOR_BYTES) + gradientValues.size() +
           keptRadiance.size();
}

#define VKDR_SET_ACCUMULATOR(name, ...)         \
    params.name = name.buffer.address();         \
    params.name##CopyStride = name.copyStride;   \
    params.name##FirstValue = name.firstValue;   \
    params.name##ValueCount = name.sums;

void AdjointBuffers::setAddresses(gpu::RenderParams& params) const {
    VKDR_ADJOINT_PATH_ARRAYS(VKDR_SET_ADDRESS)
    VKDR_GRADIENT_ACCUMULATORS(VKDR_SET_ACCUMULATOR)
    params.gradientValues = gradientValues.address();
    params.gradientValueCount = gradientValueCount;
    params.target = target.address();
    params.imageAdjoint = imageAdjoint.address();
    params.lossSum = lossSum.address();
    params.filmBaseline = filmBaseline.address();
}

#undef VKDR_ALLOCATE_PATH_ARRAY
#undef VKDR_SET_ADDRESS
#undef VKDR_ALLOCATE_ACCUMULATOR
#undef VKDR_ACCUMULATOR_BYTES
#undef VKDR_SET_ACCUMULATOR

}  // namespace vkdr
