// Pins the host's view of the structs in shaders/lib/device_types.h to std430.
#include <cstddef>

#include "device_types.h"

namespace vkdr::gpu {

static_assert(sizeof(GpuMaterial) == 48);
static_assert(offsetof(GpuMaterial, baseColorTexture) == 32);
static_assert(sizeof(GpuMedium) == 32);
static_assert(offsetof(GpuMedium, g) == 12 && offsetof(GpuMedium, sigma_s) == 16);
static_assert(sizeof(GpuTexture) == 16);
static_assert(sizeof(GpuTriangleInfo) == 16);
static_assert(sizeof(GpuCamera) == 80);
static_assert(offsetof(GpuCamera, tanHalfFovY) == 48);
static_assert(sizeof(DispatchArgs) == 16);
static_assert(offsetof(QueueCountersData, dispatch) == 16);
static_assert(sizeof(QueueCountersData) == 96);
static_assert(offsetof(RenderParams, background) == 80);
static_assert(offsetof(RenderParams, triangleVertices) == 96);
static_assert(offsetof(RenderParams, pathCapacity) == 96 + 38 * 8);
static_assert(sizeof(RenderParams) % 16 == 0);
static_assert(sizeof(PassConstants) == 32);

}  // namespace vkdr::gpu
