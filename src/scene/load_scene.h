#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_file_access.h"

namespace vkdr {

struct LoadedScene {
    Scene scene;
    std::vector<std::string> warnings;                 // things in the file that were ignored or approximated
    std::vector<std::filesystem::path> externalFiles;  // the buffers and images it read, links resolved
};

// Reads a .gltf or .glb file into a flattened, world-space Scene (docs/scene-format.md
// says what is read). Throws vkdr::Error, naming the file and the field at fault, for
// anything that cannot be rendered faithfully, and for an external file that `access`
// does not allow.
LoadedScene loadScene(const std::filesystem::path& file, const SceneFileAccess& access = {});

}  // namespace vkdr
