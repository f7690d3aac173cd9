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

// A ray crossing a boundary starts again off it by 1e-5 of the magnitude of the
// coordinates of the triangle it crossed, or of the triangle's size where that is larger
// (kSpawnOffsetPerMagnitude, shaders/lib/scene_access.glsl), so its path in the slab is
// short by up to that much at each of its two crossings: a relative error of up to
// sigma_a x twice that offset in the transmittance, beside float's. Objects elsewhere
// in the scene do not enter it.
double offsetTolerance(const TestMesh& slab) {
    double largest = 0.0;
    for (const glm::uvec3& t : slab.triangles) {
        const glm::dvec3 v0 = slab.positions[t.x], v1 = slab.positions[t.y], v2 = slab.positions[t.z];
        const double size = std::sqrt(glm::length(glm::cross(v1 - v0, v2 - v0)));
        for (const glm::dvec3& v : {v0, v1, v2}) {
            largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z), size});
        }
    }
    const double sigmaMax = std::max({kSigmaA.x, kSigmaA.y, kSigmaA.z});
    return 1e-5 + sigmaMax * 2.0 * 1e-5 * largest / std::cos(0.5 * kYfov * std::sqrt(2.0));
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
                      offsetTolerance(scene.meshes[1]));
}

// Rays leave a surface by an offset that follows the surface's own coordinates: an
// object 1e5 away, out of view, leaves the unit slab's transmittance as it was.
TEST_F(BeerLambertTest, AFarAwayObjectLeavesTheSlabAsItWas) {
    TestGltf scene = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f));
    scene.materials.push_back(diffuseMaterial("far", glm::vec3(0.5f)));
    scene.meshes.push_back(box(glm::vec3(-1.0f, -1.0f, -1.0e5f), glm::vec3(1.0f, 1.0f, -1.0e5f + 2.0f), 2));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      offsetTolerance(scene.meshes[1]));
}

TEST_F(BeerLambertTest, KhrVolumeSpelling) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance
    const float distance = 2.0f;
    glm::vec3 color = glm::exp(-kSigmaA * distance);
    TestGltf scene = slabScene(khrVolumeMaterial("slab", color, distance));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      offsetTolerance(scene.meshes[1]));
}

}  // namespace
}  // namespace vkdr::test
