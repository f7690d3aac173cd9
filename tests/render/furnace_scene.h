#pragma once
// The furnace: a camera inside a closed box whose walls emit kFurnaceLe and reflect
// `albedo`. With conservative media inside (sigma_a = 0) every direction sees
// Le / (1 - albedo), whatever the media's sigma_s and g.
#include <filesystem>

#include <glm/glm.hpp>

#include "image/image.h"
#include "test_gltf.h"

namespace vkdr::test {

inline const glm::vec3 kFurnaceLe(1.0f, 0.5f, 0.25f);

TestGltf furnace(glm::vec3 albedo);

// The coefficients of a medium per unit density.
struct MediumCoefficients {
    glm::vec3 sigmaA{0.0f};
    glm::vec3 sigmaS{0.0f};
    glm::vec3 emission{0.0f};
};

// A furnace holding a unit box of the medium "sparse" whose 16^3 grid, written to `dir`,
// has one voxel of density 1 in every majorant cell (at index `denseAt` modulo 8 on each
// axis) among voxels of `elsewhere`: the majorant is 1 everywhere, the density far less
// in most places. Returns the scene file.
std::filesystem::path furnaceWithOneDenseVoxelPerCell(glm::vec3 albedo, const MediumCoefficients& sparse, int denseAt,
                                                      float elsewhere, const std::filesystem::path& dir);

// Every pixel of a furnace estimates the same radiance: expects the image's mean within 5
// of its standard errors of `expected` in each channel (a false alarm has probability
// 6e-7 per channel), plus 1e-6 for float rounding where the image has no noise.
void expectUniformRadiance(const Image& image, glm::dvec3 expected);

}  // namespace vkdr::test
