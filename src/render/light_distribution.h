#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// The lights next-event estimation chooses from, in proportion to their power (emitted
// flux / pi): emissive triangles (area x mean emitted radiance x sides that emit) and
// placed punctual lights (Scene::lightPlacements).
struct LightDistribution {
    // gpu::kPunctualEmitter | placement index, then emissive triangles (scene order).
    std::vector<uint32_t> sources;
    std::vector<float> cdf;             // sources.size() + 1 entries from 0 to 1
    std::vector<float> trianglePmf;     // per scene triangle; 0 for non-emitters
    std::vector<float> placementPmf;    // per light placement
};

// Each material's mean emitted radiance: its emission times the mean of its emission
// texture. The light distribution depends on the parameters only through these and
// the punctual lights' intensities.
std::vector<glm::vec3> meanEmittedRadiance(const Scene& scene);

// `radiance`: meanEmittedRadiance(scene); `sceneRadius`: of a sphere around the scene,
// across which a directional light's flux is counted.
LightDistribution buildLightDistribution(const Scene& scene, std::span<const glm::vec3> radiance,
                                         double sceneRadius);

}  // namespace vkdr
