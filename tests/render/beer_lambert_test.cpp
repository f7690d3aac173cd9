// Beer-Lambert: an emitter seen through an absorbing slab. Each channel's pixel
// expectation is Le exp(-sigma_a d / cos(theta)), in both glTF spellings of a medium.
#include <cmath>

#include "render_test_support.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

const glm::vec3 kLe(1.0f, 2.0f, 3.0f);
const glm::vec3 kSigmaA(0.2f, 0.7f, 1.5f);
constexpr float kSlabThickness = 1.0f;
constexpr float kYfov = 0.1f;
constexpr int kSide = 12;
constexpr uint32_t kSpp = 4096;

TestGltf slabScene(const nlohmann::json& mediumMaterial) {
    TestGltf g;
    g.materials = {emissiveMaterial("light", kLe, false), mediumMaterial};
    g.meshes = {quadZ(0.0f, 0.0f, 3.0f, 3.0f, false, 0),
                box(glm::vec3(-2.0f, -2.0f, -0.5f * kSlabThickness), glm::vec3(2.0f, 2.0f, 0.5f * kSlabThickness), 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -5.0f);
    g.yfov = kYfov;
    return g;
}

// Path length through the slab of the ray through image position (x, y) in pixels.
double slabPath(double x, double y) {
    double t = std::tan(0.5 * kYfov);
    double ndcX = x / kSide * 2.0 - 1.0, ndcY = y / kSide * 2.0 - 1.0;
    double lx = ndcX * t, ly = ndcY * t;
    return kSlabThickness * std::sqrt(1.0 + lx * lx + ly * ly);
}

void expectBeerLambert(const Image& image) {
    ASSERT_TRUE(allFinite(image));
    // Per sample, channel c is Le T_c / mean(T) with probability mean(T) (spectral MIS
    // free flight; an absorption event ends the path with 0), so its variance is
    // Le^2 T_c^2 (1 / mean(T) - 1).
    glm::dvec3 sumError(0.0), sumVariance(0.0);
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            constexpr int kSub = 16;
            glm::dvec3 expected(0.0), variance(0.0);
            for (int sy = 0; sy < kSub; ++sy) {
                for (int sx = 0; sx < kSub; ++sx) {
                    double d = slabPath(x + (sx + 0.5) / kSub, y + (sy + 0.5) / kSub);
                    glm::dvec3 tr = glm::exp(-glm::dvec3(kSigmaA) * d);
                    double meanTr = (tr.x + tr.y + tr.z) / 3.0;
                    expected += glm::dvec3(kLe) * tr;
                    variance += glm::dvec3(kLe) * glm::dvec3(kLe) * tr * tr * (1.0 / meanTr - 1.0);
                }
            }
            expected /= double(kSub * kSub);
            variance /= double(kSub * kSub) * kSpp;
            for (int c = 0; c < 3; ++c) {
                double value = image.pixel(x, y)[c];
                EXPECT_NEAR(value, expected[c], 6.0 * std::sqrt(variance[c]) + 1e-5 * expected[c])
                    << "pixel " << x << "," << y << " channel " << c;
                sumError[c] += value - expected[c];
                sumVariance[c] += variance[c];
            }
        }
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(std::abs(sumError[c]), 4.0 * std::sqrt(sumVariance[c])) << "channel " << c;
    }
}

class BeerLambertTest : public RenderTest {};

TEST_F(BeerLambertTest, OwnExtensionSpelling) {
    auto file = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f)).write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}));
}

TEST_F(BeerLambertTest, KhrVolumeSpelling) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance
    const float distance = 2.0f;
    glm::vec3 color = glm::exp(-kSigmaA * distance);
    auto file = slabScene(khrVolumeMaterial("slab", color, distance)).write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}));
}

}  // namespace
}  // namespace vkdr::test
