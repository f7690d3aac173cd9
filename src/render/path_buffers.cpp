#include "render/path_buffers.h"

#include <algorithm>

#include "vk/context.h"

namespace vkdr {
namespace {

Buffer perPath(const VulkanContext& context, uint32_t capacity, const char* name) {
    return Buffer(context, uint64_t(capacity) * 16, MemoryUse::Device, name);
}

}  // namespace

GradientCopies::GradientCopies(const VulkanContext& context, uint32_t floatsPerCopy, const char* name)
    : floats(floatsPerCopy),
      copyStride((floatsPerCopy + gpu::kGradientCopyAlignment - 1) / gpu::kGradientCopyAlignment *
                 gpu::kGradientCopyAlignment),
      buffer(context, uint64_t(gpu::kGradientCopies) * copyStride * 4, MemoryUse::Device, name) {}

std::vector<float> GradientCopies::roomForCopies() const {
    return std::vector<float>(size_t(gpu::kGradientCopies) * copyStride);
}

std::vector<float> GradientCopies::sumOfCopies(std::span<const float> copies) const {
    std::vector<float> sum(floats, 0.0f);
    for (uint32_t copy = 0; copy < gpu::kGradientCopies; ++copy) {
        for (uint32_t i = 0; i < floats; ++i) {
            sum[i] += copies[size_t(copy) * copyStride + i];
        }
    }
    return sum;
}

PathBuffers::PathBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount)
    : capacity(capacity),
      rayOrigin(perPath(context, capacity, "ray origin")),
      rayDirection(perPath(context, capacity, "ray direction")),
      beta(perPath(context, capacity, "beta")),
      radiance(perPath(context, capacity, "radiance")),
      misVertex(perPath(context, capacity, "mis vertex")),
      hit(perPath(context, capacity, "hit")),
      pathInfo(perPath(context, capacity, "path info")),
      vertexInfo(perPath(context, capacity, "vertex info")),
      shadowOrigin(perPath(context, capacity, "shadow origin")),
      shadowDirection(perPath(context, capacity, "shadow direction")),
      shadowContribution(perPath(context, capacity, "shadow contribution")),
      queueCounters(context, sizeof(gpu::QueueCountersData), MemoryUse::Device, "queue counters"),
      queueItems(context, uint64_t(capacity) * gpu::kQueueCount * 4, MemoryUse::Device, "queue items"),
      film(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "film"),
      countersReadback(context, sizeof(gpu::QueueCountersData), MemoryUse::Readback, "queue counters readback") {}

uint64_t PathBuffers::deviceBytes() const {
    return uint64_t(capacity) * kBytesPerPath + film.size() + queueCounters.size();
}

AdjointBuffers::AdjointBuffers(const VulkanContext& context, uint32_t capacity, uint32_t pixelCount,
                               uint32_t mediumCount, uint32_t materialCount, uint32_t texelCount,
                               uint64_t keptPaths)
    : pendingFactor(perPath(context, capacity, "pending factor")),
      adjointState(perPath(context, capacity, "adjoint state")),
      vertexUv(perPath(context, capacity, "vertex uv")),
      shadowScatterGradient(perPath(context, capacity, "shadow scatter gradient")),
      shadowEmissionGradient(perPath(context, capacity, "shadow emission gradient")),
      shadowVertex(perPath(context, capacity, "shadow vertex")),
      target(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "target"),
      imageAdjoint(context, uint64_t(pixelCount) * 32, MemoryUse::Device, "image adjoint"),  // two halves
      lossSum(context, 16, MemoryUse::Device, "loss sum"),
      filmBaseline(context, uint64_t(pixelCount) * 16, MemoryUse::Device, "film baseline"),
      mediumGradients(context, std::max(1u, mediumCount) * gpu::kMediumGradientStride, "medium gradients"),
      baseColorGradients(context, std::max(1u, materialCount) * 4, "base colour gradients"),
      emissionGradients(context, std::max(1u, materialCount) * 4, "emission gradients"),
      texelGradients(context, std::max(1u, texelCount) * 16, MemoryUse::Device, "texel gradients") {
    if (keptPaths > 0) {
        keptRadiance = Buffer(context, keptPaths * 16, MemoryUse::Device, "kept radiance");
    }
}

uint64_t AdjointBuffers::deviceBytes() const {
    return pendingFactor.size() * 6 + target.size() + imageAdjoint.size() + filmBaseline.size() +
           mediumGradients.buffer.size() + baseColorGradients.buffer.size() + emissionGradients.buffer.size() +
           texelGradients.size() + keptRadiance.size();
}

}  // namespace vkdr
