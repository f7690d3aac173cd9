#pragma once
// The furnace: a camera inside a closed box whose walls emit kFurnaceLe and reflect
// `albedo`. With conservative media inside (sigma_a = 0) every direction sees
// Le / (1 - albedo), whatever the media's sigma_s and g.
#include <glm/glm.hpp>

#include "image/image.h"
#include "test_gltf.h"

namespace vkdr::test {

inline const glm::vec3 kFurnaceLe(1.0f, 0.5f, 0.25f);

TestGltf furnace(glm::vec3 albedo);

// Every pixel of a furnace estimates the same radiance: expects the image's mean within 5
// of its standard errors of `expected` in each channel (a false alarm has probability
// 6e-7 per channel), plus 1e-6 for float rounding where the image has no noise.
void expectUniformRadiance(const Image& image, glm::dvec3 expected);

}  // namespace vkdr::test
