// The camera at the centre of an emitting sphere, inside a smaller closed boundary
// enclosing an absorbing medium: the renderer must find that the camera starts in the
// enclosed medium. Each pixel expects Le exp(-sigma_a d), d the distance to the
// tessellated boundary, computed here on the host against the loaded triangles.
#include <cmath>

#include "bvh/bvh.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

const glm::vec3 kLe(2.0f, 1.0f, 0.5f);
const glm::vec3 kSigmaA(0.3f, 0.6f, 1.2f);
constexpr int kSide = 16;
constexpr uint32_t kSpp = 128;
constexpr float kYfov = 1.0f;

class CameraInMediumTest : public RenderTest {};

TEST_F(CameraInMediumTest, AbsorbingSphereAroundTheCamera) {
    TestGltf g;
    g.materials = {emissiveMaterial("shell", kLe, true), vkdrMediumMaterial("ink", kSigmaA, glm::vec3(0.0f), 0.0f)};
    g.meshes = {sphere(glm::vec3(0.0f), 2.0f, 3, 0), sphere(glm::vec3(0.0f), 1.5f, 3, 1)};
    g.yfov = kYfov;
    auto file = g.write(tempDir(), "sphere");
    Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 4});

    Scene scene = loadScene(file).scene;
    std::vector<glm::uvec3> boundary;
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.materials[scene.triangleMaterial[t]].isMediumBoundary()) {
            boundary.push_back(scene.triangles[t]);
        }
    }
    Bvh bvh = buildBvh(scene.positions, boundary);
    const double tanHalf = std::tan(0.5 * kYfov);
    expectPixelsMatch(image, kSpp, 1e-4, [&](int x, int y) {
        constexpr int kSub = 8;
        std::vector<double> distances;
        for (int s = 0; s < kSub * kSub; ++s) {
            double ndcX = (x + (s % kSub + 0.5) / kSub) / kSide * 2.0 - 1.0;
            double ndcY = (y + (s / kSub + 0.5) / kSub) / kSide * 2.0 - 1.0;
            // The camera looks along +Z (a half turn about Y): camera x maps to world -x.
            glm::vec3 direction = glm::normalize(glm::vec3(-ndcX * tanHalf, -ndcY * tanHalf, 1.0));
            auto hit = closestHit(bvh, scene.positions, boundary, glm::vec3(0.0f), direction, 1e30f);
            EXPECT_TRUE(hit.has_value());
            distances.push_back(hit ? hit->t : 0.0);
        }
        return absorbedEmitter(glm::dvec3(kLe), glm::dvec3(kSigmaA), distances);
    });
}

}  // namespace
}  // namespace vkdr::test
