#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

// Extension names this loader reads beyond the Khronos ones.
inline constexpr const char* kMediumExtension = "VKDR_participating_media";
inline constexpr const char* kBackgroundExtension = "VKDR_background";

// The medium enclosed by a material, named `mediumName`, or nullopt for an ordinary
// surface. Two spellings make a material a medium boundary:
//  - VKDR_participating_media {sigma_a, sigma_s, g} (takes precedence), or
//  - KHR_materials_transmission 1 with KHR_materials_ior 1 and KHR_materials_volume,
//    whose attenuation gives sigma_a = -ln(attenuationColor) / attenuationDistance.
// Transmission with ior != 1 (refraction) or a factor other than 0 or 1 fails.
std::optional<Medium> readMaterialMedium(const tinygltf::Material& material,
                                         size_t materialIndex, const std::string& mediumName,
                                         GltfDiagnostics& diagnostics);

// The root-level VKDR_participating_media {name, sigma_a, sigma_s, g} filling all space
// outside enclosed media; its name defaults to "scene".
std::optional<Medium> readSceneMedium(const tinygltf::Model& model, GltfDiagnostics& diagnostics);

// Fails for a channel in which a ray leaving the scene through the scene-wide medium
// would gather more than a radiance may have (unboundedSceneEmission). Call once the
// scene's density grids are read.
void requireAttenuatedSceneEmission(const Scene& scene, GltfDiagnostics& diagnostics);

// The root-level VKDR_background {radiance}, black when absent.
glm::vec3 readBackground(const tinygltf::Model& model, GltfDiagnostics& diagnostics);

}  // namespace vkdr
