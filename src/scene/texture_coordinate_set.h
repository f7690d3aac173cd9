#pragma once
#include <string>
#include <string_view>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// The TEXCOORD_<n> set a texture reference looks up: its `texCoord`, or its
// KHR_texture_transform's where that has one (glTF: the extension's replaces it).
int textureCoordinateSet(const tinygltf::TextureInfo& info, std::string_view field,
                         const GltfDiagnostics& diagnostics);

// The set a surface material's colour textures (base colour, emission) look up, which its
// primitives' uvs are read from; 0 without textures. Where the two name different sets,
// the scene keeps one set of uvs: a warning, and the base colour texture's.
int materialTextureCoordinateSet(const tinygltf::Material& material, const std::string& field,
                                 GltfDiagnostics& diagnostics);

}  // namespace vkdr
