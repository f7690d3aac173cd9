// Single scattering against quadrature: a camera ray through an infinite fog, lit by a
// small one-sided emitter beside the ray, at max depth 1 (one scattering vertex). The
// pixel is the integral over the ray of sigma_s T(t) times the phase-weighted,
// attenuated radiance arriving from the emitter; Henyey-Greenstein with g != 0 makes it
// depend on the direction convention of the phase function, which furnaces cannot see.
#include <cmath>

#include "render_test_support.h"
#include "single_scattering_quadrature.h"

namespace vkdr::test {
namespace {

class SingleScatteringTest : public RenderTest, public ::testing::WithParamInterface<double> {};

TEST_P(SingleScatteringTest, MatchesQuadrature) {
    FogSetup fog;
    fog.g = GetParam();
    auto file = fog.scene().write(tempDir(), "single");
    const glm::dvec3 expected = singleScattering(fog).radiance;

    // Independent renders of one pixel: their spread gives the standard error.
    SCOPED_TRACE("g = " + std::to_string(fog.g));
    expectPixelNear(pixelOverSeeds(file, {.spp = 8192, .maxDepth = 1}, 16), expected);
}

INSTANTIATE_TEST_SUITE_P(Anisotropies, SingleScatteringTest, ::testing::Values(-0.6, 0.0, 0.5));

}  // namespace
}  // namespace vkdr::test
