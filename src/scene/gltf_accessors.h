#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"

namespace vkdr {

// Typed copies of accessor data. Each read checks the accessor index, its buffer view
// and buffer indices, that the buffers hold every element, and that the element type is
// one the attribute allows. `field` names the referring property, e.g.
// "meshes[0].primitives[1].attributes.POSITION".

// Float three-vectors: POSITION, NORMAL.
std::vector<glm::vec3> readVec3s(const tinygltf::Model& model, int accessor,
                                     const GltfDiagnostics& diagnostics, std::string_view field);

// Float, or normalized unsigned byte / short; integers that are not normalized are
// refused, naming the accessor.
std::vector<glm::vec2> readTexcoords(const tinygltf::Model& model, int accessor,
                                     const GltfDiagnostics& diagnostics, std::string_view field);

// COLOR_0: RGB or RGBA (alpha dropped), float or normalized unsigned byte / short, every
// channel in [0, 1]: glTF's range, and a colour multiplies an albedo that must stay <= 1.
// Integers that are not normalized are refused, naming the accessor.
std::vector<glm::vec3> readColors(const tinygltf::Model& model, int accessor, const GltfDiagnostics& diagnostics,
                                  std::string_view field);

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                  const GltfDiagnostics& diagnostics, std::string_view field);

}  // namespace vkdr
