// Single scattering against quadrature: a camera ray through an infinite fog, lit by a
// small one-sided emitter beside the ray, at max depth 1 (one scattering vertex). The
// pixel is the integral over the ray of sigma_s T(t) times the phase-weighted,
// attenuated radiance arriving from the emitter; Henyey-Greenstein with g != 0 makes it
// depend on the direction convention of the phase function, which furnaces cannot see.
#include <cmath>

#include "render_test_support.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

const glm::dvec3 kLe(4.0, 3.0, 2.0);
const glm::dvec3 kSigmaA(0.1, 0.05, 0.0);
const glm::dvec3 kSigmaS(0.3, 0.5, 0.8);
constexpr double kYfov = 0.01;
// The emitter: a square in the plane x = 1.5 around (1.5, 0, 2), facing -x.
constexpr double kLightX = 1.5, kLightZ = 2.0, kLightHalf = 0.25;

double hg(double mu, double g) {
    double d = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d));
}

// Midpoint quadrature over the pixel's directions, the ray distance and the emitter.
glm::dvec3 singleScattering(double g) {
    const glm::dvec3 sigmaT = kSigmaA + kSigmaS;
    constexpr int kPixelSteps = 3, kLightSteps = 24, kRaySteps = 1600;
    constexpr double kRayEnd = 80.0;
    const double tanHalf = std::tan(0.5 * kYfov);
    glm::dvec3 sum(0.0);
    for (int p = 0; p < kPixelSteps * kPixelSteps; ++p) {
        double ndcX = ((p % kPixelSteps) + 0.5) / kPixelSteps * 2.0 - 1.0;
        double ndcY = ((p / kPixelSteps) + 0.5) / kPixelSteps * 2.0 - 1.0;
        glm::dvec3 direction = glm::normalize(glm::dvec3(-ndcX * tanHalf, -ndcY * tanHalf, 1.0));
        for (int i = 0; i < kRaySteps; ++i) {
            double t = (i + 0.5) * kRayEnd / kRaySteps;
            glm::dvec3 x = t * direction;
            glm::dvec3 inScattered(0.0);
            for (int j = 0; j < kLightSteps * kLightSteps; ++j) {
                glm::dvec3 y(kLightX, -kLightHalf + (j % kLightSteps + 0.5) * 2.0 * kLightHalf / kLightSteps,
                             kLightZ - kLightHalf + (j / kLightSteps + 0.5) * 2.0 * kLightHalf / kLightSteps);
                glm::dvec3 toLight = y - x;
                double r = glm::length(toLight);
                double cosLight = toLight.x / r;
                inScattered += hg(glm::dot(direction, toLight / r), g) * glm::exp(-sigmaT * r) * cosLight / (r * r);
            }
            inScattered *= (2.0 * kLightHalf) * (2.0 * kLightHalf) / (kLightSteps * kLightSteps);
            sum += kSigmaS * glm::exp(-sigmaT * t) * inScattered * kLe * (kRayEnd / kRaySteps);
        }
    }
    return sum / double(kPixelSteps * kPixelSteps);
}

class SingleScatteringTest : public RenderTest, public ::testing::WithParamInterface<double> {};

TEST_P(SingleScatteringTest, MatchesQuadrature) {
    const double g = GetParam();
    TestGltf scene;
    scene.materials = {emissiveMaterial("lamp", glm::vec3(kLe), false)};
    TestMesh lamp;
    lamp.positions = {{kLightX, -kLightHalf, kLightZ - kLightHalf}, {kLightX, kLightHalf, kLightZ - kLightHalf},
                      {kLightX, kLightHalf, kLightZ + kLightHalf}, {kLightX, -kLightHalf, kLightZ + kLightHalf}};
    lamp.triangles = {{0, 2, 1}, {0, 3, 2}};  // facing -x
    scene.meshes = {lamp};
    scene.extensions["VKDR_participating_media"] = {{"name", "fog"},
                                                    {"sigma_a", {kSigmaA.x, kSigmaA.y, kSigmaA.z}},
                                                    {"sigma_s", {kSigmaS.x, kSigmaS.y, kSigmaS.z}},
                                                    {"g", g}};
    scene.yfov = float(kYfov);
    auto file = scene.write(tempDir(), "single");
    const glm::dvec3 expected = singleScattering(g);

    // Independent renders of one pixel: their spread gives the standard error.
    constexpr int kRenders = 16;
    glm::dvec3 sum(0.0), sumSquares(0.0);
    for (uint32_t seed = 0; seed < kRenders; ++seed) {
        Image image = renderFile(file, {.width = 1, .height = 1, .spp = 8192, .maxDepth = 1, .seed = seed});
        glm::dvec3 v(image.rgb[0], image.rgb[1], image.rgb[2]);
        sum += v;
        sumSquares += v * v;
    }
    glm::dvec3 mean = sum / double(kRenders);
    glm::dvec3 standardError = glm::sqrt((sumSquares / double(kRenders) - mean * mean) / double(kRenders - 1));
    for (int c = 0; c < 3; ++c) {
        // 16 renders: the standard error is itself uncertain, so allow 6 of them.
        EXPECT_NEAR(mean[c], expected[c], 6.0 * standardError[c] + 1e-3 * expected[c])
            << "channel " << c << ", g = " << g;
    }
}

INSTANTIATE_TEST_SUITE_P(Anisotropies, SingleScatteringTest, ::testing::Values(-0.6, 0.0, 0.5));

}  // namespace
}  // namespace vkdr::test
