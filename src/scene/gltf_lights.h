#pragma once
#include <optional>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

inline constexpr const char* kPunctualLightsExtension = "KHR_lights_punctual";

// The file's KHR_lights_punctual definitions, in its order, checked: a known type, a
// colour and intensity whose product is a valid lights/<name>/intensity, spot cones
// with 0 <= inner < outer <= pi/2, unique names (a light's own, else "lights[i]").
std::vector<PunctualLight> readPunctualLights(const tinygltf::Model& model, GltfDiagnostics& diagnostics);

// The light node `nodeIndex` places (its KHR_lights_punctual.light), at the node's
// origin shining along its -Z, or nullopt when it places none.
std::optional<LightPlacement> placeNodeLight(const tinygltf::Model& model, size_t nodeIndex,
                                             const glm::mat4& nodeToWorld, const GltfDiagnostics& diagnostics);

}  // namespace vkdr
