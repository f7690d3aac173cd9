// Loss gradients against quadrature: single scattering of one pixel through a fog lit by
// a small emitter (max depth 1), where the radiance and its derivatives with respect to
// sigma_a, sigma_s and g are 1D x 2D integrals. The adjoint's mean over seeds must match
// within five of its standard errors. Also with sigma_s = 0 in every channel and in one,
// where only the derivative mode of the replay can find the gradient, and with the
// medium enclosed in a box that the camera ray enters and every shadow ray leaves, and
// with a density grid in that box, and with the emitter close to the ray.
#include <cmath>

#include "diff/rendered_loss_gradient.h"
#include "diff/gradient_over_seeds.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "single_scattering_quadrature.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

constexpr int kSeeds = 8;
const glm::dvec3 kTarget(0.01, 0.02, 0.03);

struct FogGradientCase {
    const char* label;
    glm::dvec3 sigmaS;
    double g;
    std::optional<FogSetup::Box> enclosure = std::nullopt;
    std::optional<FogSetup::LinearDensity> density = std::nullopt;  // a density grid medium
    double lightX = FogSetup().lightX;  // the emitter's distance from the camera ray
    double lightHalf = FogSetup().lightHalf;
};

void PrintTo(const FogGradientCase& c, std::ostream* os) {
    *os << c.label;
}

class FogGradientTest : public RenderTest, public ::testing::WithParamInterface<FogGradientCase> {};

TEST_P(FogGradientTest, MatchesQuadrature) {
    FogSetup fog;
    fog.sigmaS = GetParam().sigmaS;
    fog.g = GetParam().g;
    fog.enclosure = GetParam().enclosure;
    fog.density = GetParam().density;
    fog.lightX = GetParam().lightX;
    fog.lightHalf = GetParam().lightHalf;
    const std::filesystem::path dir = tempDir();
    if (fog.density) {
        writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
    }
    Scene scene = loadScene(fog.scene().write(dir, "fog")).scene;
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
    const std::vector<std::vector<MeanAndError>> gradients = gradientOverSeeds(lg, scene, kSeeds);
    for (size_t p = 0; p < names.size(); ++p) {
        for (size_t c = 0; c < expected[p].size(); ++c) {
            const MeanAndError& adjoint = gradients[p][c];
            EXPECT_NEAR(adjoint.mean, expected[p][c], 5.0 * adjoint.error + 1e-3 * std::abs(expected[p][c]))
                << names[p] << "[" << c << "]: standard error " << adjoint.error;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Fogs, FogGradientTest,
    ::testing::Values(FogGradientCase{"Forward", {0.3, 0.5, 0.8}, 0.4},
                      FogGradientCase{"Backward", {0.3, 0.5, 0.8}, -0.5},
                      FogGradientCase{"NoScattering", {0.0, 0.0, 0.0}, 0.4},
                      FogGradientCase{"NoScatteringInGreen", {0.3, 0.0, 0.8}, 0.2},
                      // The light (x = 1.5) is outside the box: shadow rays cross its face x = 1.
                      FogGradientCase{"Enclosed", {0.3, 0.5, 0.8}, 0.4, FogSetup::Box{{-1.0, -1.0, 1.0}, {1.0, 1.0, 4.0}}},
                      // Density rising along the camera ray, from a grid: the factors are
                      // estimated by delta and ratio tracking, their derivatives at points.
                      FogGradientCase{"DensityGrid", {0.3, 0.5, 0.8}, 0.4, FogSetup::Box{{-1.0, -1.0, 1.0}, {1.0, 1.0, 4.0}},
                                      FogSetup::LinearDensity{0.3, 0.5, "density.vdb"}},
                      // A small emitter 0.1 from the ray: most of the light comes from
                      // equiangular sampling's next events (docs/design.md).
                      FogGradientCase{"NearTheLight", {0.3, 0.5, 0.8}, 0.4, std::nullopt, std::nullopt, 0.1,
                                      0.05}),
    [](const ::testing::TestParamInfo<FogGradientCase>& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace vkdr::test
