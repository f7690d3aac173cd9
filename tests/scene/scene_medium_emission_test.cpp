// The bound on a homogeneous scene-wide medium's emission / (sigma_a + sigma_s): which
// parameters it couples, and the ranges that keep it, checked against the scene's own
// test once the values are stored as floats.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "scene/scene_medium_emission.h"

namespace vkdr::test {
namespace {

Scene sceneWideFog(glm::vec3 sigma_a, glm::vec3 sigma_s, glm::vec3 emission) {
    Scene scene;
    scene.media.push_back({"fog", sigma_a, sigma_s, 0.0f, emission});
    scene.sceneMedium = 0;
    return scene;
}

TEST(SceneMediumEmission, CouplesTheSceneWideHomogeneousMediumsSigmasAndEmission) {
    Scene scene = sceneWideFog(glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(0.0f));
    EXPECT_EQ(sceneWideEmissionMember(scene, "media/fog/sigma_a"), EmissionBoundMember::SigmaA);
    EXPECT_EQ(sceneWideEmissionMember(scene, "media/fog/sigma_s"), EmissionBoundMember::SigmaS);
    EXPECT_EQ(sceneWideEmissionMember(scene, "media/fog/emission"), EmissionBoundMember::Emission);
    EXPECT_FALSE(sceneWideEmissionMember(scene, "media/fog/g"));
    EXPECT_FALSE(sceneWideEmissionMember(scene, "media/smoke/sigma_a"));
    scene.media.push_back({"smoke", glm::vec3(1.0f)});
    scene.sceneMedium = 1;
    EXPECT_FALSE(sceneWideEmissionMember(scene, "media/fog/sigma_a"));
    scene.media[1].densityGrid = 0;  // a grid is finite: nothing to bound
    EXPECT_FALSE(sceneWideEmissionMember(scene, "media/smoke/sigma_a"));
    scene.sceneMedium = kNoMedium;
    EXPECT_FALSE(sceneWideEmissionMember(scene, "media/fog/sigma_a"));
}

// A ratio over the bound by its floats' rounding alone says so in its digits: 6e10 and
// 0.06 are stored as 6.0000002e10 and 0.0599999987.
TEST(SceneMediumEmission, ARefusalShowsTheFloatsItCompared) {
    std::optional<UnboundedSceneEmission> unbounded =
        unboundedSceneEmission(sceneWideFog(glm::vec3(0.06f), glm::vec3(0.0f), glm::vec3(6e10f)));
    ASSERT_TRUE(unbounded);
    EXPECT_NE(unbounded->problem.find("= 6.0000002e+10 / 0.0599999987 = 1.00000006e+12 in channel 0, beyond the 1e+12"),
              std::string::npos)
        << unbounded->problem;
}

// Each member set to its range's end, from values far outside the bound, leaves the
// scene within it as floats: emissions from ordinary down to below float's normal range.
TEST(SceneMediumEmission, TheEndsOfTheRangesKeepTheBoundAsFloats) {
    const ValueRange any{-INFINITY, INFINITY};
    for (double emission : {3.0, 1e-20, 1e-30, 1e-40}) {
        const EmissionAndAttenuation values{0.0, 0.0, emission};
        for (EmissionBoundMember member : {EmissionBoundMember::SigmaA, EmissionBoundMember::SigmaS}) {
            const bool sigma_a = member == EmissionBoundMember::SigmaA;
            ValueRange range = emissionBoundedRange(values, member, any, 1e-5);
            EXPECT_GT(range.lower, 0.0) << (sigma_a ? "sigma_a" : "sigma_s") << " at emission " << emission;
            glm::vec3 sigma(float(range.lower));
            Scene scene = sigma_a ? sceneWideFog(sigma, glm::vec3(0.0f), glm::vec3(float(emission)))
                                  : sceneWideFog(glm::vec3(0.0f), sigma, glm::vec3(float(emission)));
            std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(scene);
            EXPECT_FALSE(unbounded) << (sigma_a ? "sigma_a" : "sigma_s") << " at emission " << emission << ": "
                                    << unbounded->problem;
        }
    }
    // The largest emission over a given attenuation; none over none.
    const EmissionAndAttenuation thin{2e-13, 1e-13, 5.0};
    ValueRange range = emissionBoundedRange(thin, EmissionBoundMember::Emission, {0.0, 1e12}, 1e-5);
    EXPECT_NEAR(range.upper, 0.3, 1e-5);
    std::optional<UnboundedSceneEmission> unbounded =
        unboundedSceneEmission(sceneWideFog(glm::vec3(2e-13f), glm::vec3(1e-13f), glm::vec3(float(range.upper))));
    EXPECT_FALSE(unbounded) << unbounded->problem;
    EXPECT_EQ(emissionBoundedRange({0.0, 0.0, 1.0}, EmissionBoundMember::Emission, {0.0, 1e12}, 0.0).upper, 0.0);
    // Ranges already inside the bound are left as they are.
    EXPECT_EQ(emissionBoundedRange({0.5, 0.5, 1.0}, EmissionBoundMember::SigmaA, {0.0, INFINITY}, 1e-5).lower, 0.0);
    EXPECT_EQ(emissionBoundedRange({0.0, 0.0, 0.0}, EmissionBoundMember::SigmaS, {0.0, INFINITY}, 1e-5).lower, 0.0);
}

}  // namespace
}  // namespace vkdr::test
