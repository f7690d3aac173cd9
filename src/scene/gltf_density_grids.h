#pragma once
#include <filesystem>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"
#include "scene/scene_file_access.h"

namespace vkdr {

// Reads the grids that VKDR_participating_media objects reference, on materials and at
// the root: "density": {"uri", "grid" (default "density"), "node" (optional)}, which makes
// its medium heterogeneous, and "emissionGrid" (the same, its grid by default "flame"),
// the strength that multiplies the medium's emission, and "albedoGrid" (its grid by
// default "color", RGB or grey), which scales its scattering. Each becomes a Scene::densityGrids
// entry placed by the node's world transform times the grid's own. Appends the grid files
// to `read`.
void readDensityGrids(const tinygltf::Model& model, const SceneFiles& files, GltfDiagnostics& diagnostics,
                      Scene& scene, std::vector<std::filesystem::path>& read);

}  // namespace vkdr
