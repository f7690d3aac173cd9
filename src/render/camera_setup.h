#pragma once
#include <string>

#include "device_types.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace vkdr {

// Picks the camera named in the settings (or the first) and the image size: both sides
// when given, else one side from the camera's aspect ratio, else 512 wide. Refuses an
// orthographic camera whose view a medium boundary crosses (scene/orthographic_view.h).
gpu::GpuCamera setUpCamera(const Scene& scene, const RenderSettings& settings);

// The camera named `name`, or the first for an empty name; an unknown name is an error
// listing the scene's cameras.
const Camera& findCamera(const Scene& scene, const std::string& name);

// Refuses a scene without a camera, saying how to export one; `file` names the scene in
// the message ("" where the caller has no file).
void requireCamera(const Scene& scene, const std::string& file);

}  // namespace vkdr
