#pragma once
#include "device_types.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace vkdr {

// Picks the camera named in the settings (or the first) and the image size: both sides
// when given, else one side from the camera's aspect ratio, else 512 wide.
gpu::GpuCamera setUpCamera(const Scene& scene, const RenderSettings& settings);

}  // namespace vkdr
