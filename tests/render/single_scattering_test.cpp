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

// A point light beside the ray: a delta light, which next-event estimation alone reaches
// (equiangular sampling places collisions near it), in a chromatic fog with g = 0.5,
// with and without equiangular sampling.
TEST_F(RenderTest, SingleScatteringFromAPointLightMatchesQuadrature) {
    FogSetup fog;
    fog.g = 0.5;
    fog.lightX = 0.6;
    fog.pointIntensity = glm::dvec3(2.0, 1.0, 0.5);
    auto file = fog.scene().write(tempDir(), "point");
    const glm::dvec3 expected = singleScattering(fog).radiance;
    for (bool equiangular : {true, false}) {
        SCOPED_TRACE(equiangular ? "with equiangular sampling" : "distance sampling only");
        expectPixelNear(pixelOverSeeds(file, {.spp = 4096, .maxDepth = 1, .equiangularSampling = equiangular}, 16),
                        expected);
    }
}

// An emitter 0.1 from the camera ray: distance sampling alone finds the collisions close
// to it rarely and weights them by 1 / r^2 (fireflies); equiangular sampling places them
// there. Both estimators match quadrature, with and without equiangular sampling, and
// equiangular sampling's standard error is the smaller.
TEST_F(RenderTest, SingleScatteringNearALightMatchesQuadratureWithLessNoise) {
    FogSetup fog;
    fog.lightX = 0.1;
    fog.lightHalf = 0.05;
    auto file = fog.scene().write(tempDir(), "near");
    const glm::dvec3 expected = singleScattering(fog).radiance;
    constexpr int kRenders = 16;
    const auto withEquiangular = pixelOverSeeds(file, {.spp = 4096, .maxDepth = 1}, kRenders);
    const auto distanceOnly =
        pixelOverSeeds(file, {.spp = 4096, .maxDepth = 1, .equiangularSampling = false}, kRenders);
    {
        SCOPED_TRACE("with equiangular sampling");
        expectPixelNear(withEquiangular, expected);
    }
    {
        SCOPED_TRACE("distance sampling only");
        expectPixelNear(distanceOnly, expected);
    }
    // Here equiangular sampling's standard error is about a tenth of the other's. Each
    // error comes from 16 renders, so their ratio is within a factor 4.1 of the true one
    // but for a chance of 1e-6 (the F distribution with 15 and 15 degrees of freedom):
    // a half bounds it.
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(withEquiangular[c].error, distanceOnly[c].error / 2.0) << "channel " << c;
    }
}

// An emitter that points of the ray see under up to 2 sr: next-event estimation at a
// free-flight collision samples it in solid angle, the equiangular next event in area,
// and the two distance strategies weigh each other with both densities of the light
// point (distance_mis.glsl). Weights that did not sum to one would bias the pixel.
TEST_F(RenderTest, SingleScatteringBesideALargeLightMatchesQuadrature) {
    FogSetup fog;
    fog.lightX = 0.5;
    fog.lightHalf = 0.5;
    auto file = fog.scene().write(tempDir(), "large");
    expectPixelNear(pixelOverSeeds(file, {.spp = 4096, .maxDepth = 1}, 16), singleScattering(fog).radiance);
}

}  // namespace
}  // namespace vkdr::test
