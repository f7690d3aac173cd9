// Pins the host's view of the structs in shaders/lib/device_types.h to std430.
#include <cstddef>

#include "device_types.h"
#include "scene/scene.h"
#include "vk/commands.h"

namespace vkdr::gpu {

static_assert(sizeof(GpuMaterial) == 128);
static_assert(offsetof(GpuMaterial, baseColorTexture) == 32 && offsetof(GpuMaterial, baseColorUvRows) == 48);
static_assert(offsetof(GpuMaterial, wrap) == 112);
static_assert(kWrapRepeat == uint32_t(TextureWrap::Repeat) && kWrapClampToEdge == uint32_t(TextureWrap::ClampToEdge) &&
              kWrapMirroredRepeat == uint32_t(TextureWrap::MirroredRepeat));
static_assert(sizeof(GpuMedium) == 64);
static_assert(offsetof(GpuMedium, g) == 12 && offsetof(GpuMedium, sigma_s) == 16);
static_assert(offsetof(GpuMedium, densityGrid) == 28 && offsetof(GpuMedium, emission) == 32);
static_assert(sizeof(GpuDensityGrid) == 128);
static_assert(offsetof(GpuDensityGrid, firstVoxel) == 48 && offsetof(GpuDensityGrid, majorantCells) == 96 &&
              offsetof(GpuDensityGrid, tracking) == 112);
static_assert(sizeof(GpuTexture) == 16);
static_assert(sizeof(GpuPunctualLight) == 64);
static_assert(offsetof(GpuPunctualLight, direction) == 16 && offsetof(GpuPunctualLight, intensity) == 32 &&
              offsetof(GpuPunctualLight, light) == 48);
static_assert(sizeof(GpuTriangleInfo) == 16);
static_assert(sizeof(GpuCamera) == 80);
static_assert(offsetof(GpuCamera, tanHalfFovY) == 48 && offsetof(GpuCamera, orthographicHalfHeight) == 68);
static_assert(sizeof(DispatchArgs) == 16);
static_assert(offsetof(QueueCountersData, dispatch) == 16);
static_assert(sizeof(QueueCountersData) == 144);
static_assert(offsetof(RenderParams, background) == 80);
static_assert(offsetof(RenderParams, triangleVertices) == 96);
// Device addresses, 8 bytes each, then the scalars: no padding between them on either side.
#define VKDR_COUNT(...) +1
constexpr size_t kAddresses = 16 + 3 + 5 + 0 VKDR_PATH_ARRAYS(VKDR_COUNT) VKDR_ADJOINT_PATH_ARRAYS(VKDR_COUNT)
    VKDR_GRADIENT_ACCUMULATORS(VKDR_COUNT);
static_assert(offsetof(RenderParams, pathCapacity) == offsetof(RenderParams, triangleVertices) + kAddresses * 8);
static_assert(sizeof(PassConstants) == 32);
static_assert(kWorkgroupSize == vkdr::kWorkgroupSize, "the stages' workgroups and the dispatches' sizes agree");

}  // namespace vkdr::gpu
