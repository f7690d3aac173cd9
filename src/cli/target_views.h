#pragma once
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "scene/scene.h"

namespace vkdr {

// "CAMERA=FILE" names the view's camera; a plain FILE is the scene's first camera.
// Errors name the --target argument at fault.
TargetView readTarget(const std::string& argument, const Scene& scene);

}  // namespace vkdr
