#include "render/light_distribution.h"

#include <algorithm>
#include <cmath>

#include "device_types.h"

namespace vkdr {
namespace {

glm::vec3 averageTexel(const Texture& texture) {
    glm::dvec3 sum(0.0);
    for (const glm::vec4& t : texture.texels) {
        sum += glm::dvec3(t);
    }
    return texture.texels.empty() ? glm::vec3(0.0f) : glm::vec3(sum / double(texture.texels.size()));
}

double meanChannel(glm::vec3 rgb) {
    return (double(rgb.r) + double(rgb.g) + double(rgb.b)) / 3.0;
}

// Emitted flux / pi: a point light's 4 pi I, a spot light's at most 2 pi (1 - cos outer) I,
// a directional light's pi R^2 E.
double punctualPower(const PunctualLight& light, double radius) {
    const double intensity = meanChannel(light.intensity);
    switch (light.type) {
    case PunctualLight::Type::Point: return 4.0 * intensity;
    case PunctualLight::Type::Spot: return 2.0 * (1.0 - double(light.cosOuterCone)) * intensity;
    case PunctualLight::Type::Directional: return radius * radius * intensity;
    }
    return 0.0;
}

// The share of the choices the punctual lights keep between them however dim they are
// (each at least this over their number, of the other lights' power), so that one whose
// intensity is 0 is still sampled and gets a gradient to grow from.
constexpr double kPunctualPowerFloor = 0.01;

// The device chooses a light with a uniform number on the grid of multiples of
// 1 / kChoiceSteps (rng.glsl's toUnitFloat: 24-bit floats). The CDF's ends lie on that
// grid, so the probability of a choice is exactly its interval's length, which the
// estimators divide by; a CDF of rounded floats would be chosen with a probability that
// differs from its pmf by up to a grid step, a large share of a light among millions.
constexpr uint32_t kChoiceSteps = 1u << 24;
constexpr float kChoiceStep = 1.0f / float(kChoiceSteps);

// The CDF of `power` (summing to `total`) in grid steps, from 0 to kChoiceSteps, with at
// least one step for every light while the grid has room for all of them: a light
// that next-event estimation never chose would go dark where only it reaches.
std::vector<uint32_t> quantisedCumulativeShares(const std::vector<double>& power, double total) {
    const size_t count = power.size();
    const uint32_t leastStep = count <= kChoiceSteps ? 1u : 0u;
    std::vector<uint32_t> steps(count + 1, 0u);
    double running = 0.0;
    for (size_t i = 0; i < count; ++i) {
        running += power[i];
        const double share = std::min(running / total, 1.0) * double(kChoiceSteps);
        const uint64_t lowest = uint64_t(steps[i]) + leastStep;
        const uint64_t highest = kChoiceSteps - uint64_t(count - 1 - i) * leastStep;
        steps[i + 1] = uint32_t(std::clamp<uint64_t>(uint64_t(std::llround(share)), lowest, highest));
    }
    steps[count] = kChoiceSteps;
    return steps;
}

}  // namespace

std::vector<glm::vec3> meanEmittedRadiance(const Scene& scene) {
    std::vector<glm::vec3> radiance;
    for (const Material& material : scene.materials) {
        radiance.push_back(material.emissionTexture >= 0
                               ? material.emission * averageTexel(scene.textures[material.emissionTexture])
                               : material.emission);
    }
    return radiance;
}

LightDistribution buildLightDistribution(const Scene& scene, std::span<const glm::vec3> radiance,
                                         double sceneRadius) {
    std::vector<double> materialPower(scene.materials.size(), 0.0);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        materialPower[m] = meanChannel(radiance[m]) * (scene.materials[m].doubleSided ? 2.0 : 1.0);
    }

    LightDistribution lights;
    lights.trianglePmf.assign(scene.triangles.size(), 0.0f);
    lights.placementPmf.assign(scene.lightPlacements.size(), 0.0f);
    // Punctual lights first, then the emissive triangles in the scene's order.
    std::vector<double> power;
    for (size_t i = 0; i < scene.lightPlacements.size(); ++i) {
        lights.sources.push_back(gpu::kPunctualEmitter | static_cast<uint32_t>(i));
        power.push_back(punctualPower(scene.punctualLights[scene.lightPlacements[i].light], sceneRadius));
    }
    const size_t punctualCount = power.size();
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        double p = materialPower[scene.triangleMaterial[t]];
        if (p <= 0.0) {
            continue;
        }
        const glm::uvec3& tri = scene.triangles[t];
        glm::dvec3 e1 = glm::dvec3(scene.positions[tri[1]] - scene.positions[tri[0]]);
        glm::dvec3 e2 = glm::dvec3(scene.positions[tri[2]] - scene.positions[tri[0]]);
        double area = 0.5 * glm::length(glm::cross(e1, e2));
        if (area > 0.0) {
            lights.sources.push_back(static_cast<uint32_t>(t));
            power.push_back(p * area);
        }
    }
    double total = 0.0;
    for (double p : power) {
        total += p;
    }
    const double floor = total > 0.0 ? kPunctualPowerFloor * total / double(std::max<size_t>(punctualCount, 1)) : 1.0;
    for (size_t i = 0; i < punctualCount; ++i) {
        total += std::max(power[i], floor) - power[i];
        power[i] = std::max(power[i], floor);
    }
    const std::vector<uint32_t> steps = quantisedCumulativeShares(power, total);
    lights.cdf.push_back(0.0f);
    for (size_t i = 0; i < power.size(); ++i) {
        lights.cdf.push_back(float(steps[i + 1]) * kChoiceStep);
        // The probability the device's choice has: the uniform numbers on the grid of
        // kChoiceSteps that fall in this light's interval.
        const float pmf = float(steps[i + 1] - steps[i]) * kChoiceStep;
        if (i < punctualCount) {
            lights.placementPmf[i] = pmf;
        } else {
            lights.trianglePmf[lights.sources[i]] = pmf;
        }
    }
    return lights;
}

}  // namespace vkdr
