// The light distribution's pmf is the probability with which the device chooses each
// light: findLight (lights.glsl) takes the first light whose CDF end exceeds a uniform
// number on the grid of multiples of 2^-24 (rng.glsl's toUnitFloat), and every estimator
// divides by the pmf. Checked here by counting the grid's numbers in each interval.
#include <gtest/gtest.h>

#include <cmath>

#include "device_types.h"
#include "render/light_distribution.h"

namespace vkdr::test {
namespace {

constexpr double kGridNumbers = 16777216.0;  // 2^24

// How many of the numbers k / 2^24, k = 0 .. 2^24 - 1, findLight maps to light i: those
// in [cdf[i], cdf[i + 1]).
double chosenNumbers(const LightDistribution& lights, size_t i) {
    return std::ceil(double(lights.cdf[i + 1]) * kGridNumbers) - std::ceil(double(lights.cdf[i]) * kGridNumbers);
}

// One emissive material of radiance `radiance` and, per entry of `areas`, a triangle of
// that area with it.
Scene emitters(const std::vector<float>& areas, float radiance) {
    Scene scene;
    Material material;
    material.emission = glm::vec3(radiance);
    material.emitter = true;
    scene.materials.push_back(material);
    for (float area : areas) {
        const uint32_t first = uint32_t(scene.positions.size());
        const float edge = std::sqrt(2.0f * area);
        scene.positions.push_back(glm::vec3(0.0f));
        scene.positions.push_back(glm::vec3(edge, 0.0f, 0.0f));
        scene.positions.push_back(glm::vec3(0.0f, edge, 0.0f));
        scene.triangles.push_back(glm::uvec3(first, first + 1, first + 2));
        scene.triangleMaterial.push_back(0);
        scene.triangleOutsideMedium.push_back(kNoMedium);
    }
    return scene;
}

LightDistribution distributionOf(const Scene& scene) {
    const std::vector<glm::vec3> radiance = meanEmittedRadiance(scene);
    return buildLightDistribution(scene, radiance, 10.0);
}

float pmfOfSource(const LightDistribution& lights, size_t i) {
    const uint32_t source = lights.sources[i];
    return (source & gpu::kPunctualEmitter) != 0u ? lights.placementPmf[source & ~gpu::kPunctualEmitter]
                                                   : lights.trianglePmf[source];
}

void expectPmfIsTheChoiceProbability(const LightDistribution& lights) {
    ASSERT_EQ(lights.cdf.size(), lights.sources.size() + 1);
    EXPECT_EQ(lights.cdf.front(), 0.0f);
    EXPECT_EQ(lights.cdf.back(), 1.0f);
    for (size_t i = 0; i < lights.sources.size(); ++i) {
        ASSERT_EQ(double(pmfOfSource(lights, i)) * kGridNumbers, chosenNumbers(lights, i)) << "light " << i;
    }
}

// A few bright triangles beside thousands whose share is far below one grid step: the
// small ones used to get a pmf of their share but an interval of no grid number.
TEST(LightDistributionTest, PmfIsTheProbabilityOfTheChoice) {
    std::vector<float> areas(3000, 1e-9f);
    areas[0] = 1.0f;
    areas[1500] = 3.0f;
    areas[2999] = 0.5f;
    const LightDistribution lights = distributionOf(emitters(areas, 2.0f));
    expectPmfIsTheChoiceProbability(lights);
    for (size_t i = 0; i < lights.sources.size(); ++i) {
        EXPECT_GT(lights.trianglePmf[lights.sources[i]], 0.0f) << "light " << i << " is never chosen";
    }
}

// Between lights the grid resolves, the pmf follows the power within a grid step.
TEST(LightDistributionTest, PmfFollowsThePower) {
    const std::vector<float> areas = {1.0f, 3.0f, 0.25f, 0.75f};
    const LightDistribution lights = distributionOf(emitters(areas, 1.0f));
    expectPmfIsTheChoiceProbability(lights);
    const double total = 5.0;
    for (size_t i = 0; i < areas.size(); ++i) {
        EXPECT_NEAR(lights.trianglePmf[i], areas[i] / total, 1.0 / kGridNumbers) << "triangle " << i;
    }
}

// A punctual light of intensity 0 keeps a share, so it is sampled and gets a gradient.
TEST(LightDistributionTest, DarkPunctualLightsAreStillChosen) {
    Scene scene = emitters({1.0f, 2.0f}, 1.0f);
    PunctualLight dark;
    dark.intensity = glm::vec3(0.0f);
    scene.punctualLights.push_back(dark);
    scene.lightPlacements.push_back(LightPlacement{});
    scene.lightPlacements.push_back(LightPlacement{});
    const LightDistribution lights = distributionOf(scene);
    expectPmfIsTheChoiceProbability(lights);
    EXPECT_GT(lights.placementPmf[0], 0.0f);
    EXPECT_GT(lights.placementPmf[1], 0.0f);
}

}  // namespace
}  // namespace vkdr::test
