#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// Emissive triangles chosen for next-event estimation in proportion to their power
// (area x mean emitted radiance x sides that emit).
struct LightDistribution {
    std::vector<uint32_t> triangles;    // emissive triangles, scene order
    std::vector<float> cdf;             // triangles.size() + 1 entries from 0 to 1
    std::vector<float> trianglePmf;     // per scene triangle; 0 for non-emitters
};

// Each material's mean emitted radiance: its emission times the mean of its emission
// texture. The light distribution depends on the parameters only through these.
std::vector<glm::vec3> meanEmittedRadiance(const Scene& scene);

// `radiance`: meanEmittedRadiance(scene).
LightDistribution buildLightDistribution(const Scene& scene, std::span<const glm::vec3> radiance);

}  // namespace vkdr
