#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene/load_scene.h"
#include "scene/scene.h"
#include "scene/scene_file_access.h"

namespace vkdr {

// The scene file and its parameter overrides, shared by every subcommand.
struct SceneOptions {
    std::string file;
    std::vector<std::string> assignments;  // NAME=VALUE
    SceneFileAccess access;                // --allow-outside-files
};

void addSceneOptions(CLI::App& command, SceneOptions& options);

// Loads the scene, prints the loader's warnings, applies the --set overrides.
LoadedScene loadSceneWithOverrides(const SceneOptions& options);

}  // namespace vkdr
