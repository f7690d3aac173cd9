#pragma once
#include <filesystem>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Parses a .gltf or .glb file with tinygltf, buffers and images included (external
// files, data URIs and GLB chunks alike). Fails with tinygltf's own error text.
tinygltf::Model readGltfModel(const std::filesystem::path& file, GltfDiagnostics& diagnostics);

}  // namespace vkdr
