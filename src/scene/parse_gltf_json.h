#pragma once
#include <string_view>

#include <nlohmann/json.hpp>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// A glTF file's JSON, refused before tinygltf reads it where it nests values more than
// 512 levels deep (tinygltf's parser recurses once per level, and tens of thousands
// would overflow the stack) or gives a key twice in one object (glTF requires unique
// keys). Text that is not JSON gives a document that is not an object, for tinygltf to
// describe.
nlohmann::json parseGltfJson(std::string_view text, const GltfDiagnostics& diagnostics);

}  // namespace vkdr
