#pragma once
#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

// Appends one Scene material per glTF material, in glTF order (so glTF material i is
// Scene::materials[i]), with the textures they use and the media they enclose.
// Unnamed materials are named by their index; a repeated name is replaced by the
// index too (with a warning), so every parameter name is unique.
void readMaterials(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene);

// Whether a glTF material's emissiveFactor is above 0 in some channel: it emits, or may
// once its emission is fitted (a strength of 0 still counts), and only then does its
// emission texture show.
bool hasEmissiveFactor(const tinygltf::Material& material);

}  // namespace vkdr
