#pragma once
#include <filesystem>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene_file_access.h"
#include "scene/source_files.h"

namespace vkdr {

// Parses a .gltf or .glb file with tinygltf, buffers and images included (external
// files, data URIs and GLB chunks alike). External files are read only as `access`
// allows; a refused one fails naming its field ("buffers[1].uri"). Otherwise fails with
// tinygltf's own error text. `file`, then each external file read, is added to `sources`.
tinygltf::Model readGltfModel(const std::filesystem::path& file, const SceneFileAccess& access,
                              GltfDiagnostics& diagnostics, std::vector<SourceFile>& sources);

}  // namespace vkdr
