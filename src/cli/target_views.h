#pragma once
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "optimize/run_identity.h"
#include "scene/scene.h"

namespace vkdr {

// A --target argument: "CAMERA=FILE" where CAMERA is one of the scene's cameras (the
// longest that fits, so that camera names and file names may both hold '='), or else a
// FILE for the scene's first camera. An argument holding '=' that is neither is refused,
// naming the cameras.
TargetFile parseTargetArgument(const std::string& argument, const Scene& scene);

// The view of a --target argument. Errors name the argument at fault; a target with a
// NaN, infinite or unrepresentably large pixel is refused, naming the pixel.
TargetView readTarget(const std::string& argument, const Scene& scene);

// Every --target argument, in order; warns (on stderr) when two of them view the same
// camera, whose render the loss would then compare with both.
std::vector<TargetView> readTargets(const std::vector<std::string>& arguments, const Scene& scene);

}  // namespace vkdr
