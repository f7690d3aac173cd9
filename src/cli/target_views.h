#pragma once
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "scene/scene.h"

namespace vkdr {

// "CAMERA=FILE" names the view's camera; a plain FILE is the scene's first camera.
// Errors name the --target argument at fault; a target with a NaN, infinite or
// unrepresentably large pixel is refused, naming the pixel.
TargetView readTarget(const std::string& argument, const Scene& scene);

// Every --target argument, in order; warns (on stderr) when two of them view the same
// camera, whose render the loss would then compare with both.
std::vector<TargetView> readTargets(const std::vector<std::string>& arguments, const Scene& scene);

}  // namespace vkdr
