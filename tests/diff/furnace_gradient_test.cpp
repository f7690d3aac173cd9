// In a furnace filled with conservative media (sigma_a = 0), the image is Le / (1 - rho)
// whatever their sigma_s and g, so those gradients are zero: the adjoint's mean over
// seeds must be within four standard errors of 0; likewise with media that emit what
// they absorb, and there also along sigma_a with the emission following it. sigma_a, which does change the image,
// must have a gradient many standard errors from 0, so the test sees real gradients.
// Long free flights make single gradients heavy-tailed, so many cheap seeds (rather
// than a few expensive ones) give a standard error that can be trusted.
#include <cmath>

#include "diff/rendered_loss_gradient.h"
#include "diff/gradient_over_seeds.h"
#include "furnace_scene.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
constexpr int kSeeds = 96;

class FurnaceGradientTest : public RenderTest {};

TEST_F(FurnaceGradientTest, ScatteringAndAnisotropyDoNotChangeTheImage) {
    TestGltf g = furnace(glm::vec3(0.5f));
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.0, 0.0, 0.0}}, {"sigma_s", {0.5, 1.0, 2.0}}, {"g", 0.6}};
    // Two conservative boxes side by side: shadow rays from one through the other cross
    // three media, more than the shadow stage records, so it traces them a second time.
    g.materials.push_back(vkdrMediumMaterial("left", glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.5f), -0.4f));
    g.materials.push_back(vkdrMediumMaterial("right", glm::vec3(0.0f), glm::vec3(1.5f), 0.3f));
    g.meshes.push_back(box(glm::vec3(-0.8f, -0.5f, 0.2f), glm::vec3(-0.2f, 0.5f, 0.8f), 1));
    g.meshes.push_back(box(glm::vec3(0.2f, -0.5f, 0.2f), glm::vec3(0.8f, 0.5f, 0.8f), 2));
    Scene scene = loadScene(g.write(tempDir(), "furnace")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    const std::vector<std::string> names = {"media/fog/sigma_s", "media/fog/g",   "media/left/sigma_s",
                                            "media/right/g",     "media/fog/sigma_a"};
    // Deep enough that truncation, which does depend on sigma_s, is far below the noise.
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, names, {.spp = 8, .maxDepth = 400}, LossKind::L2);
    const std::vector<std::vector<MeanAndError>> gradients = gradientOverSeeds(lg, scene, kSeeds);
    for (size_t p = 0; p < names.size(); ++p) {
        for (size_t c = 0; c < gradients[p].size(); ++c) {
            const MeanAndError& gradient = gradients[p][c];
            ASSERT_GT(gradient.error, 0.0) << names[p] << "[" << c << "]";
            if (names[p] == "media/fog/sigma_a") {
                EXPECT_LT(gradient.mean, -10.0 * gradient.error) << names[p] << "[" << c << "]";
            } else {
                EXPECT_NEAR(gradient.mean, 0.0, 4.0 * gradient.error)
                    << names[p] << "[" << c << "]: standard error " << gradient.error;
            }
        }
    }
}

// Media that emit what they absorb, emission = sigma_a L* with L* = Le / (1 - rho), keep
// the furnace at L* whatever their sigma_s and g, and whatever sigma_a where the emission
// follows it: dLoss/dsigma_a + L* dLoss/demission is 0 in each channel (a scene-wide fog,
// and a box nested in it, the camera in both), as are the sigma_s and g gradients. The
// combination's standard error comes from its value seed by seed, since the two
// gradients share their paths; sigma_a alone, which darkens the image, must be many
// standard errors from 0.
TEST_F(FurnaceGradientTest, MediaInEquilibriumHaveNoGradientAlongIt) {
    const glm::vec3 rho(0.5f);
    const glm::vec3 radiance = kFurnaceLe / (1.0f - rho);
    TestGltf g = furnace(rho);
    const glm::vec3 fogSigmaA(0.3f, 0.6f, 1.2f), boxSigmaA(1.5f, 0.5f, 1.0f);
    const glm::vec3 fogEmission = fogSigmaA * radiance, boxEmission = boxSigmaA * radiance;
    g.extensions["VKDR_participating_media"] = {{"name", "fog"},
                                                {"sigma_a", {fogSigmaA.x, fogSigmaA.y, fogSigmaA.z}},
                                                {"sigma_s", {0.5, 1.0, 0.2}},
                                                {"g", 0.4},
                                                {"emission", {fogEmission.x, fogEmission.y, fogEmission.z}}};
    nlohmann::json nested = vkdrMediumMaterial("box", boxSigmaA, glm::vec3(1.0f, 2.0f, 0.5f), -0.3f);
    nested["extensions"]["VKDR_participating_media"]["emission"] = {boxEmission.x, boxEmission.y, boxEmission.z};
    g.materials.push_back(nested);
    g.meshes.push_back(box(glm::vec3(-0.6f), glm::vec3(0.6f), 1));
    Scene scene = loadScene(g.write(tempDir(), "equilibrium")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    const std::vector<std::string> names = {"media/fog/sigma_a", "media/fog/emission", "media/box/sigma_a",
                                            "media/box/emission", "media/fog/sigma_s", "media/box/g"};
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, names, {.spp = 8, .maxDepth = 400}, LossKind::L2);
    const auto samples = gradientSamplesOverSeeds(lg, scene, kSeeds);
    for (size_t medium : {0u, 2u}) {
        for (size_t c = 0; c < 3; ++c) {
            std::vector<double> along;
            for (size_t s = 0; s < kSeeds; ++s) {
                along.push_back(samples[medium][c][s] + double(radiance[int(c)]) * samples[medium + 1][c][s]);
            }
            const MeanAndError combined = meanAndError(along);
            const MeanAndError sigmaA = meanAndError(samples[medium][c]);
            EXPECT_NEAR(combined.mean, 0.0, 4.0 * combined.error) << names[medium] << "[" << c << "]";
            EXPECT_LT(sigmaA.mean, -10.0 * sigmaA.error) << names[medium] << "[" << c << "]";
        }
    }
    for (size_t p = 4; p < names.size(); ++p) {
        for (size_t c = 0; c < samples[p].size(); ++c) {
            const MeanAndError gradient = meanAndError(samples[p][c]);
            ASSERT_GT(gradient.error, 0.0) << names[p] << "[" << c << "]";
            EXPECT_NEAR(gradient.mean, 0.0, 4.0 * gradient.error) << names[p] << "[" << c << "]";
        }
    }
}

// Walls of base colour factor f and vertex colour c reflect f c, so every pixel is
// I = Le / (1 - f c) and dI/df = Le c / (1 - f c)^2. The L2 loss against black, a mean
// of I^2 over pixels and channels, has the gradient (2 / 3) I dI/df in each channel
// (its two factors from independent halves of the samples: docs/gradients.md).
TEST_F(FurnaceGradientTest, BaseColourGradientCarriesTheVertexColour) {
    const float f = 0.5f;
    const glm::dvec3 c(0.25, 0.5, 1.0);
    TestGltf g = furnace(glm::vec3(f));
    g.meshes[0].colors.assign(g.meshes[0].positions.size(), glm::vec4(glm::vec3(c), 1.0f));
    Scene scene = loadScene(g.write(tempDir(), "coloured")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, {"materials/walls/base_color"},
                            {.spp = 8, .maxDepth = 400}, LossKind::L2);
    const std::vector<MeanAndError> gradient = gradientOverSeeds(lg, scene, 32)[0];
    for (int channel = 0; channel < 3; ++channel) {
        const double le = kFurnaceLe[channel], fc = f * c[channel];
        const double expected = 2.0 / 3.0 * (le / (1.0 - fc)) * (le * c[channel] / ((1.0 - fc) * (1.0 - fc)));
        EXPECT_NEAR(gradient[size_t(channel)].mean, expected, 5.0 * gradient[size_t(channel)].error)
            << "channel " << channel << ": standard error " << gradient[size_t(channel)].error;
    }
}

}  // namespace
}  // namespace vkdr::test
