// Beer-Lambert: an emitter seen through an absorbing slab. Each channel's pixel
// expectation is Le exp(-sigma_a d / cos(theta)), in both glTF spellings of a medium;
// a ray passes the slab weighted by its transmittance, so a pixel varies only with the
// positions its samples take in it.
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

// A ray crossing a boundary starts again 1e-5 scene extents off it (render/gpu_scene.cpp),
// so its path in the slab is short by up to that much at each of its two crossings: a
// relative error of up to sigma_a x 2e-5 x extent in the transmittance, beside float's.
double offsetTolerance(const TestGltf& scene) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const TestMesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    const double sigmaMax = std::max({kSigmaA.x, kSigmaA.y, kSigmaA.z});
    return 1e-5 + sigmaMax * 2e-5 * glm::length(hi - lo) / std::cos(0.5 * kYfov * std::sqrt(2.0));
}

void expectBeerLambert(const Image& image, double tolerance) {
    expectPixelsMatch(image, kSpp, tolerance, [](int x, int y) {
        constexpr int kSub = 16;
        std::vector<double> distances;
        for (int s = 0; s < kSub * kSub; ++s) {
            distances.push_back(slabPath(x + (s % kSub + 0.5) / kSub, y + (s / kSub + 0.5) / kSub));
        }
        return absorbedEmitter(glm::dvec3(kLe), glm::dvec3(kSigmaA), distances);
    });
}

class BeerLambertTest : public RenderTest {};

TEST_F(BeerLambertTest, OwnExtensionSpelling) {
    TestGltf scene = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      offsetTolerance(scene));
}

TEST_F(BeerLambertTest, KhrVolumeSpelling) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance
    const float distance = 2.0f;
    glm::vec3 color = glm::exp(-kSigmaA * distance);
    TestGltf scene = slabScene(khrVolumeMaterial("slab", color, distance));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      offsetTolerance(scene));
}

}  // namespace
}  // namespace vkdr::test
