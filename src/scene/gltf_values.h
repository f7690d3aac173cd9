#pragma once
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Empty when `number` is finite as the float it is stored as, else why not: 1e39 is a
// finite number in the file, but beyond float's range.
std::string floatProblem(double number);

// Typed reads of extension members (tinygltf leaves extensions as untyped JSON values).
// `object` is the JSON object at path `field`; a member that is absent gives `fallback`,
// one of the wrong type or not finite fails with the member's full path.

double readNumber(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                  std::string_view field, const std::string& key, double fallback);

// An RGB triple, or a single number meaning the same value in every channel.
glm::vec3 readRgbOrScalar(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                          std::string_view field, const std::string& key, glm::vec3 fallback);

// An array of exactly two numbers.
glm::vec2 readVec2(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                   std::string_view field, const std::string& key, glm::vec2 fallback);

std::string readString(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                       std::string_view field, const std::string& key,
                       const std::string& fallback);

// The first three numbers of a factor tinygltf has already parsed (baseColorFactor,
// emissiveFactor), checked to be finite.
glm::vec3 rgbFromFactor(const GltfDiagnostics& diagnostics, const std::vector<double>& factor,
                        std::string_view field);

}  // namespace vkdr
