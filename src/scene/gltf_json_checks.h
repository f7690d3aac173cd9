#pragma once
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Whether the loader reads `extension`, or loses only detail without it (with a warning):
// the extensions whose JSON is checked, and that a file may require.
bool isUnderstoodExtension(std::string_view extension);

// Refuses, naming the field, what tinygltf would read without a word as something else:
// a null (dropped, so the default is used), an empty {} or [] in a vkdiffrender
// extension (dropped likewise), an extension that is not an object (skipped), a vector of
// the wrong length or an index of the wrong type (ignored), and values outside the
// glTF schema's bounds where the loader would otherwise go on (a camera's znear <= 0, a
// rotation that is not a unit quaternion, a node matrix that is not affine, a mesh
// without primitives), and a buffer's base64 data URI that is not base64 or does not hold
// byteLength bytes (tinygltf's message would quote the whole URI). Warns about members of a vkdiffrender extension it does not
// know, since a misspelt "sigma_s" would otherwise leave the default 0 in its place.
// Runs on the parsed JSON before tinygltf reads it; `document` must be an object.
void requireWellFormedJson(const nlohmann::json& document, GltfDiagnostics& diagnostics);

}  // namespace vkdr
