// Loss gradients against quadrature: single scattering of one pixel through a fog lit by
// a small emitter (max depth 1), where the radiance and its derivatives with respect to
// sigma_a, sigma_s and g are 1D x 2D integrals. The adjoint's mean over seeds must match
// within five of its standard errors. Also with sigma_s = 0 in every channel and in one,
// where only the derivative mode of the replay can find the gradient.
#include <cmath>

#include "diff/rendered_loss_gradient.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "single_scattering_quadrature.h"

namespace vkdr::test {
namespace {

constexpr int kSeeds = 8;
const glm::dvec3 kTarget(0.01, 0.02, 0.03);

struct FogGradientCase {
    const char* label;
    glm::dvec3 sigmaS;
    double g;
};

class FogGradientTest : public RenderTest, public ::testing::WithParamInterface<FogGradientCase> {};

TEST_P(FogGradientTest, MatchesQuadrature) {
    FogSetup fog;
    fog.sigmaS = GetParam().sigmaS;
    fog.g = GetParam().g;
    Scene scene = loadScene(fog.scene().write(tempDir(), "fog")).scene;
    const SingleScattering reference = singleScattering(fog);

    // L2 over one pixel: loss = mean_c (I_c - T_c)^2, so dloss/dI_c = 2 (I_c - T_c) / 3.
    const glm::dvec3 dLossDI = 2.0 * (reference.radiance - kTarget) / 3.0;
    const std::vector<std::string> names = {"media/fog/sigma_a", "media/fog/sigma_s", "media/fog/g"};
    const std::vector<std::vector<double>> expected = {
        {dLossDI.x * reference.dSigmaA.x, dLossDI.y * reference.dSigmaA.y, dLossDI.z * reference.dSigmaA.z},
        {dLossDI.x * reference.dSigmaS.x, dLossDI.y * reference.dSigmaS.y, dLossDI.z * reference.dSigmaS.z},
        {glm::dot(dLossDI, reference.dG)}};

    Image target{1, 1, {float(kTarget.x), float(kTarget.y), float(kTarget.z)}};
    RenderedLossGradient lg(testContext(), scene, {{"", target}}, names, {.spp = 4096, .maxDepth = 1}, LossKind::L2);
    std::vector<std::vector<double>> sum(names.size(), std::vector<double>(3, 0.0)), sumSquares = sum;
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        GradientResult r = lg.evaluate(scene, seed);
        for (size_t p = 0; p < names.size(); ++p) {
            for (size_t c = 0; c < r.parameters[p].gradient.size(); ++c) {
                sum[p][c] += r.parameters[p].gradient[c];
                sumSquares[p][c] += r.parameters[p].gradient[c] * r.parameters[p].gradient[c];
            }
        }
    }
    for (size_t p = 0; p < names.size(); ++p) {
        for (size_t c = 0; c < expected[p].size(); ++c) {
            double mean = sum[p][c] / kSeeds;
            double variance = std::max(0.0, (sumSquares[p][c] / kSeeds - mean * mean) * kSeeds / (kSeeds - 1));
            double standardError = std::sqrt(variance / kSeeds);
            EXPECT_NEAR(mean, expected[p][c], 5.0 * standardError + 1e-3 * std::abs(expected[p][c]))
                << names[p] << "[" << c << "]: standard error " << standardError;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Fogs, FogGradientTest,
    ::testing::Values(FogGradientCase{"Forward", {0.3, 0.5, 0.8}, 0.4},
                      FogGradientCase{"Backward", {0.3, 0.5, 0.8}, -0.5},
                      FogGradientCase{"NoScattering", {0.0, 0.0, 0.0}, 0.4},
                      FogGradientCase{"NoScatteringInGreen", {0.3, 0.0, 0.8}, 0.2}),
    [](const ::testing::TestParamInfo<FogGradientCase>& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace vkdr::test
