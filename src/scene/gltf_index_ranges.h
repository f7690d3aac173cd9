#pragma once
#include <nlohmann/json_fwd.hpp>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Refuses, naming the field, an index of the glTF core schema (and of KHR_lights_punctual)
// that names no entry of its array, in any object of the file, used by the scene or not:
// glTF requires every index to be in range, and the loader reads only what the scene
// uses, so a file that other readers refuse would otherwise load here. Indices that are
// not whole numbers are left to requireWellFormedJson.
void requireIndicesInRange(const nlohmann::json& document, const GltfDiagnostics& diagnostics);

}  // namespace vkdr
