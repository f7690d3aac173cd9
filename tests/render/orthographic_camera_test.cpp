// An orthographic camera: rays start across the camera's plane and run parallel. The
// camera sits in an absorbing fog, before an emitter that fills the view, with a box of
// a denser medium covering one corner of the view: each pixel expects Le exp(-integral
// of sigma_a) along its straight ray, which depends only on where on the plane the ray
// starts. The box's two edges across the view fall on pixel boundaries that say where
// the view is: a perspective camera, or a view of another size, place, aspect or
// orientation, fails it.
#include <cmath>

#include "expect_error.h"
#include "render_test_support.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

const glm::vec3 kLe(1.0f, 2.0f, 3.0f);
const glm::dvec3 kFogSigmaA(0.02, 0.05, 0.1);
constexpr float kHalfHeight = 2.0f;
constexpr float kAspect = 1.5f;
constexpr int kWidth = 24, kHeight = 16;  // pixels a quarter unit square
constexpr uint32_t kSpp = 256;
const glm::vec3 kCamera(0.5f, 0.25f, -5.0f);
constexpr float kEmitterZ = 5.0f;
constexpr float kBoxNear = -1.0f, kBoxFar = 1.5f;  // the box's extent along the view
constexpr float kBoxEdgeX = 1.0f, kBoxEdgeY = 0.75f;  // the box covers world x > 1, y > 0.75

TestGltf orthographicScene(glm::vec3 camera) {
    TestGltf g;
    // The box holds twice the fog's sigma_a.
    const glm::vec3 boxSigmaA = glm::vec3(2.0 * kFogSigmaA);
    g.materials = {emissiveMaterial("light", kLe, false),
                   vkdrMediumMaterial("dense", boxSigmaA, glm::vec3(0.0f), 0.0f)};
    g.meshes = {quadZ(0.0f, 0.0f, 20.0f, kEmitterZ, false, 0),
                box(glm::vec3(kBoxEdgeX, kBoxEdgeY, kBoxNear), glm::vec3(12.0f, 10.0f, kBoxFar), 1)};
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {kFogSigmaA.x, kFogSigmaA.y, kFogSigmaA.z}}, {"sigma_s", {0.0, 0.0, 0.0}}};
    g.cameraPosition = camera;
    g.orthographicHalfHeight = kHalfHeight;
    g.aspectRatio = kAspect;
    return g;
}

class OrthographicCameraTest : public RenderTest {};

TEST_F(OrthographicCameraTest, ParallelRaysFromAcrossTheView) {
    const auto file = orthographicScene(kCamera).write(tempDir(), "ortho");
    // The width follows the camera's aspect ratio.
    const Image image = renderFile(file, {.height = kHeight, .spp = kSpp, .maxDepth = 4});
    ASSERT_EQ(image.width, kWidth);
    const double path = kEmitterZ - kCamera.z;
    expectPixelsMatch(image, kSpp, (kSpp - 1) * 0x1p-24 + 1e-5, [&](int x, int y) {
        // The camera looks along +Z (a half turn about Y): its x is world -x; row 0 is
        // the top. Every pixel lies wholly on one side of each of the box's edges.
        const double worldX = kCamera.x - ((x + 0.5) / kWidth * 2.0 - 1.0) * kHalfHeight * kAspect;
        const double worldY = kCamera.y - ((y + 0.5) / kHeight * 2.0 - 1.0) * kHalfHeight;
        const double inBox = worldX > kBoxEdgeX && worldY > kBoxEdgeY ? kBoxFar - kBoxNear : 0.0;
        // In the box the fog gives way to twice its sigma_a: the fog's over path + inBox.
        return absorbedEmitter(glm::dvec3(kLe), kFogSigmaA, {path + inBox});
    });
    // Columns 0 to 9 lie beyond the edge x = 1 (world x from 3.5 down to 1.0), 10 on do
    // not; rows 0 to 5 above y = 0.75 (world y from 2.25 down to 0.75), 6 on do not.
    EXPECT_LT(image.pixel(9, 5)[2], image.pixel(10, 5)[2]);
    EXPECT_LT(image.pixel(9, 5)[2], image.pixel(9, 6)[2]);
}

// Rays from either side of a boundary across the view would start in different media;
// the render is refused, naming the camera and the medium.
TEST_F(OrthographicCameraTest, ABoundaryAcrossTheViewIsRefused) {
    // The camera's plane at z = 0 cuts the box (z from -1 to 1.5), which covers x > 1 of
    // a view from x = -2.5 to 3.5.
    const auto across = orthographicScene(glm::vec3(kCamera.x, kCamera.y, 0.0f)).write(tempDir(), "across");
    expectErrorMentioning([&] { renderFile(across, {.height = kHeight, .spp = 1, .maxDepth = 4}); },
                          {"orthographic camera", "medium 'dense'"});
    // Moved sideways until the view ends before the box (x < 1), it renders, all in the fog.
    const auto beside = orthographicScene(glm::vec3(-2.5f, kCamera.y, 0.0f)).write(tempDir(), "beside");
    const Image image = renderFile(beside, {.height = kHeight, .spp = 16, .maxDepth = 4});
    expectPixelsMatch(image, 16, 15 * 0x1p-24 + 1e-5, [&](int, int) {
        return absorbedEmitter(glm::dvec3(kLe), kFogSigmaA, {double(kEmitterZ)});
    });
}

TEST_F(OrthographicCameraTest, AViewBeyondFloatRangeIsRefused) {
    // Each half extent is a float (ymag 2e38, xmag 3e38), but the view's corners lie
    // 3.6e38 from its centre, beyond float range, where rays would start at infinity.
    TestGltf scene = orthographicScene(kCamera);
    scene.orthographicHalfHeight = 2e38f;
    const auto huge = scene.write(tempDir(), "huge");
    expectErrorMentioning([&] { renderFile(huge, {.height = kHeight, .spp = 1, .maxDepth = 4}); },
                          {"orthographic camera", "beyond float range"});
}

}  // namespace
}  // namespace vkdr::test
