#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// What about a scene, as it will be rendered (after --set overrides), would surprise a
// user without being an error: no light at all (the image will be black), emissive
// triangles of zero area (they emit nothing), a camera on a medium boundary. One line
// each, without "warning: ".
std::vector<std::string> sceneWarnings(const Scene& scene);

}  // namespace vkdr
