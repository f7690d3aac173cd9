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

// The film sums a pixel's samples in float, in sample order (shaders/film.comp): each
// addition rounds by at most half a unit in the last place of the partial sum, so a sum
// of N positive terms is within (N - 1) 2^-24 of itself, relatively (Higham, "Accuracy
// and Stability of Numerical Algorithms", 4.2).
constexpr double kFilmRounding = (kSpp - 1) * 0x1p-24;

// A ray crossing a boundary is traced again from off it (kSpawnOffsetPerMagnitude,
// shaders/lib/scene_access.glsl), and its segment counts the stretch it skipped
// (spawnLeadIn): its path in the slab is exact but for float's rounding of the points at
// its two crossings, a few units in the last place of the slab's largest coordinate
// over the cosine, times sigma_a in the transmittance. Objects elsewhere in the scene do
// not enter it.
double roundingTolerance(const TestMesh& slab) {
    double largest = 0.0;
    for (const glm::vec3& v : slab.positions) {
        largest = std::max({largest, double(std::abs(v.x)), double(std::abs(v.y)), double(std::abs(v.z))});
    }
    const double sigmaMax = std::max({kSigmaA.x, kSigmaA.y, kSigmaA.z});
    constexpr double kUnitsInTheLastPlace = 8.0 * 1.1920929e-7;
    return kFilmRounding + sigmaMax * 2.0 * kUnitsInTheLastPlace * largest / std::cos(0.5 * kYfov * std::sqrt(2.0));
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
                      roundingTolerance(scene.meshes[1]));
}

// Rays leave a surface by an offset that follows the surface's own coordinates: an
// object 1e5 away, out of view, leaves the unit slab's transmittance as it was.
TEST_F(BeerLambertTest, AFarAwayObjectLeavesTheSlabAsItWas) {
    TestGltf scene = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f));
    scene.materials.push_back(diffuseMaterial("far", glm::vec3(0.5f)));
    scene.meshes.push_back(box(glm::vec3(-1.0f, -1.0f, -1.0e5f), glm::vec3(1.0f, 1.0f, -1.0e5f + 2.0f), 2));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      roundingTolerance(scene.meshes[1]));
}

// 1000 from the origin a surface's spawn offset is 0.01 long: the slab keeps its
// transmittance there all the same (a skipped offset would make it 3 % brighter).
TEST_F(BeerLambertTest, ASlabFarFromTheOriginKeepsItsTransmittance) {
    TestGltf scene = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f));
    const glm::vec3 shift(1000.0f, 0.0f, 0.0f);
    for (TestMesh& mesh : scene.meshes) {
        for (glm::vec3& position : mesh.positions) {
            position += shift;
        }
    }
    scene.cameraPosition += shift;
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      roundingTolerance(scene.meshes[1]));
}

TEST_F(BeerLambertTest, KhrVolumeSpelling) {
    // sigma_a = -ln(attenuationColor) / attenuationDistance
    const float distance = 2.0f;
    glm::vec3 color = glm::exp(-kSigmaA * distance);
    TestGltf scene = slabScene(khrVolumeMaterial("slab", color, distance));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      roundingTolerance(scene.meshes[1]));
}

}  // namespace
}  // namespace vkdr::test
