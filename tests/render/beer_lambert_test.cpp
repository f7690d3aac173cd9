// Beer-Lambert: an emitter seen through an absorbing slab, and through a prism whose
// rays leave by faces at right angles to those they enter by. Each channel's pixel
// expectation is Le exp(-sigma_a d) for the path d through the medium, in both glTF
// spellings of a medium; a ray passes the medium weighted by its transmittance, so a
// pixel varies only with the positions its samples take in it.
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

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

// A ray crossing a boundary goes on from the point where it crosses it, passing over
// its triangle (traceClosest, shaders/lib/bvh_traverse.glsl): its path in the medium is
// exact but for float's rounding of the points at its two crossings, a few units in the last place of the medium's largest coordinate
// over the cosine, times sigma_a in the transmittance. Objects elsewhere in the scene do
// not enter it.
double roundingTolerance(const TestMesh& slab, double cosine = std::cos(0.5 * kYfov * std::sqrt(2.0))) {
    double largest = 0.0;
    for (const glm::vec3& v : slab.positions) {
        largest = std::max({largest, double(std::abs(v.x)), double(std::abs(v.y)), double(std::abs(v.z))});
    }
    const double sigmaMax = std::max({kSigmaA.x, kSigmaA.y, kSigmaA.z});
    constexpr double kUnitsInTheLastPlace = 8.0 * 1.1920929e-7;
    return kFilmRounding + sigmaMax * 2.0 * kUnitsInTheLastPlace * largest / cosine;
}

// Each pixel against the closed form at 16 x 16 points of it, for the path length
// `path(x, y)` through the medium at image position (x, y) in pixels.
void expectBeerLambert(const Image& image, double tolerance, double (*path)(double, double) = slabPath) {
    expectPixelsMatch(image, kSpp, tolerance, [path](int x, int y) {
        constexpr int kSub = 16;
        std::vector<double> distances;
        for (int s = 0; s < kSub * kSub; ++s) {
            distances.push_back(path(x + (s % kSub + 0.5) / kSub, y + (s / kSub + 0.5) / kSub));
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

// Rays leave a surface from the point itself, whatever else the scene holds: an object
// 1e5 away, out of view, leaves the unit slab's transmittance as it was.
TEST_F(BeerLambertTest, AFarAwayObjectLeavesTheSlabAsItWas) {
    TestGltf scene = slabScene(vkdrMediumMaterial("slab", kSigmaA, glm::vec3(0.0f), 0.0f));
    scene.materials.push_back(diffuseMaterial("far", glm::vec3(0.5f)));
    scene.meshes.push_back(box(glm::vec3(-1.0f, -1.0f, -1.0e5f), glm::vec3(1.0f, 1.0f, -1.0e5f + 2.0f), 2));
    auto file = scene.write(tempDir(), "slab");
    expectBeerLambert(renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4}),
                      roundingTolerance(scene.meshes[1]));
}

// 1000 from the origin the slab keeps its transmittance (a ray going on from 1e-5 of the
// coordinates, 0.01, off each face would see it 3 % brighter).
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

// A square prism of the medium, turned 45 degrees about the view's vertical and taller
// than the view: a ray enters by one of its two front faces and leaves by the back face
// parallel to it or by the one at right angles to it.
constexpr double kPrismHalfWidth = 0.12;
const glm::dmat3 kPrismTurn = glm::dmat3(glm::rotate(glm::dmat4(1.0), std::numbers::pi / 4.0, glm::dvec3(0.0, 1.0, 0.0)));

TestGltf prismScene(glm::vec3 shift) {
    TestGltf scene = slabScene(vkdrMediumMaterial("prism", kSigmaA, glm::vec3(0.0f), 0.0f));
    const float w = float(kPrismHalfWidth);
    scene.meshes[1] = box(glm::vec3(-w, -1.0f, -w), glm::vec3(w, 1.0f, w), 1);
    for (glm::vec3& position : scene.meshes[1].positions) {
        position = glm::vec3(kPrismTurn * glm::dvec3(position));
    }
    for (TestMesh& mesh : scene.meshes) {
        for (glm::vec3& position : mesh.positions) {
            position += shift;
        }
    }
    scene.cameraPosition += shift;
    return scene;
}

// Path length through the prism of the ray through image position (x, y) in pixels,
// in the prism's own frame (slabs method).
double prismPath(double x, double y) {
    double t = std::tan(0.5 * kYfov);
    const glm::dvec3 origin = glm::transpose(kPrismTurn) * glm::dvec3(0.0, 0.0, -5.0);
    const glm::dvec3 direction =
        glm::transpose(kPrismTurn) * glm::dvec3((x / kSide * 2.0 - 1.0) * t, (y / kSide * 2.0 - 1.0) * t, 1.0);
    double enter = 0.0, leave = 1e30;
    for (int axis = 0; axis < 3; axis += 2) {
        double a = (-kPrismHalfWidth - origin[axis]) / direction[axis];
        double b = (kPrismHalfWidth - origin[axis]) / direction[axis];
        enter = std::max(enter, std::min(a, b));
        leave = std::min(leave, std::max(a, b));
    }
    return leave > enter ? (leave - enter) * glm::length(direction) : 0.0;
}

// 1000 from the origin a ray that went on from a boundary 1e-5 of the coordinates off it
// would miss 0.01 of the medium where it leaves by a parallel face, and where it leaves
// by one at right angles, near the prism's edges, miss the face itself.
TEST_F(BeerLambertTest, APrismFarFromTheOriginKeepsItsTransmittance) {
    for (const glm::vec3 shift : {glm::vec3(0.0f), glm::vec3(1000.0f, 0.0f, 0.0f)}) {
        SCOPED_TRACE("shifted by " + std::to_string(shift.x));
        TestGltf scene = prismScene(shift);
        auto file = scene.write(tempDir(), "prism");
        const Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4});
        // The rays cross the prism's faces at 45 degrees, give or take half the field of view.
        const double tolerance = roundingTolerance(scene.meshes[1], std::cos(std::numbers::pi / 4.0 + kYfov));
        expectBeerLambert(image, tolerance, prismPath);
    }
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
