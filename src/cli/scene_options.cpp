#include "cli/scene_options.h"

#include <map>
#include <set>
#include <string_view>

#include "cli/warnings.h"
#include "scene/load_scene.h"
#include "core/error.h"
#include "render/camera_setup.h"
#include "scene/parameters.h"
#include "scene/scene_medium_emission.h"
#include "scene/scene_warnings.h"

namespace vkdr {

void addSceneOptions(CLI::App& command, SceneOptions& options) {
    command.add_option("scene", options.file, "Scene file (.gltf or .glb)")->required();
    command.add_option("--set", options.assignments,
                       "Override a parameter, e.g. --set media/fog/sigma_a=0.05,0.05,0.05 (repeatable, once per "
                       "parameter; one value sets all three channels)");
    command.add_flag("--allow-outside-files", options.access.allowOutsideFiles,
                     "Let the scene read buffers and images outside its own directory (absolute paths, ../)");
}

LoadedScene loadSceneWithOverrides(const SceneOptions& options) {
    LoadedScene loaded = loadScene(options.file, options.access);
    requireCamera(loaded.scene, options.file);
    for (const std::string& warning : loaded.warnings) {
        printWarning(warning);
    }
    // A second value would silently win over the first, as in no other option, whether
    // given under the same name or under another name of the same values.
    std::set<std::string_view> names;
    std::map<const float*, std::string_view> nameOfValues;
    for (const std::string& assignment : options.assignments) {
        applyAssignment(loaded.scene, assignment);
        const std::string_view name = assignedName(assignment);
        if (!names.insert(name).second) {
            throw Error("--set " + std::string(name) + ": given twice; set each parameter once");
        }
        const float* values = parameterStorageAddress(loaded.scene, name);
        if (values == nullptr) {
            continue;  // no values to share (a grid without active voxels)
        }
        if (const auto [first, isNew] = nameOfValues.emplace(values, name); !isNew) {
            throw Error("--set " + std::string(name) + ": names the same values as --set " +
                        std::string(first->second) + " (a texture both materials use); set them once");
        }
    }
    if (std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(loaded.scene)) {
        throw Error("--set: " + unbounded->problem);
    }
    for (const std::string& warning : sceneWarnings(loaded.scene, options.file)) {
        printWarning(warning);
    }
    return loaded;
}

}  // namespace vkdr
