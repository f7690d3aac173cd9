#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// What about a scene, as it will be rendered (after --set overrides), would surprise a
// user without being an error: no light at all (the image will be black), emissive
// triangles of zero area (they emit nothing), a camera on a medium boundary. One line
// each, without "warning: ", starting with `file`, the scene's file, as the loader's
// warnings do.
std::vector<std::string> sceneWarnings(const Scene& scene, const std::filesystem::path& file);

}  // namespace vkdr
