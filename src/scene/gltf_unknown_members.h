#pragma once
#include <nlohmann/json_fwd.hpp>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Warns about each member of a glTF core object, or of a KHR_lights_punctual light, that
// the glTF 2.0 schema does not define (as the Khronos validator does): tinygltf skips it
// without a word, so a misspelt "intensty" or "baseColorFactr" would leave the default
// in its place. The members of vkdiffrender's own extensions are checked where they are
// read (requireWellFormedJson). Objects the loader ignores (animations, skins) are not
// looked into. Runs on the parsed JSON; `document` must be an object.
void warnOfUnknownMembers(const nlohmann::json& document, GltfDiagnostics& diagnostics);

}  // namespace vkdr
