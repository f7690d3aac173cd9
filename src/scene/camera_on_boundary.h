#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// For each camera that lies on a medium boundary, within float's reach of its surface
// (1e-5 of the coordinates' magnitude): a warning naming the camera and the medium.
// The renderer's float arithmetic may count the crossing of such a surface by a ray from
// the camera or miss it, so the camera would see through the medium in some pixels only.
std::vector<std::string> camerasOnMediumBoundaries(const Scene& scene);

}  // namespace vkdr
