#pragma once
// The furnace: a camera inside a closed box whose walls emit kFurnaceLe and reflect
// `albedo`. With conservative media inside (sigma_a = 0) every direction sees
// Le / (1 - albedo), whatever the media's sigma_s and g.
#include <glm/glm.hpp>

#include "test_gltf.h"

namespace vkdr::test {

inline const glm::vec3 kFurnaceLe(1.0f, 0.5f, 0.25f);

TestGltf furnace(glm::vec3 albedo);

}  // namespace vkdr::test
