// Shadow rays stop at the first opaque surface they find within their length, and pass
// medium boundaries multiplying the transmittance of every segment. The scenes are
// furnaces whose every opaque surface, occluders included, emits Le and reflects rho, so
// the answer is known whatever blocks what: direct lighting (max depth 1) sees
// Le (1 + rho) in every pixel, and with conservative media and no depth limit
// Le / (1 - rho). A shadow ray blocked by a surface beyond its light darkens the image;
// one let through an occluder counts the light behind it as well as the occluder's own
// emission (both are sampled as lights) and brightens it.
//
// Inside the furnace: a box of medium with an opaque box inside it (opaque triangles
// past the medium's entry, so shadow rays meet boundaries and opaque hits in one
// traversal) and an opaque box beside it, all turned so that the traversal meets far
// faces before near ones: a shadow ray that took the first boundary it found for the
// nearest would skip the occluders in between.
#include <cmath>

#include "furnace_scene.h"
#include "render_test_support.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 24;
const glm::dvec3 kRho(0.5, 0.3, 0.7);

// A box turned 45 degrees about x and then about y: the bounding boxes of its large
// slanted faces overlap each other and whatever is inside, so the traversal often meets
// a far face before a near one.
TestMesh turnedBox(glm::vec3 lo, glm::vec3 hi, int material) {
    TestMesh mesh = box(lo, hi, material);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float c = std::sqrt(0.5f);
    for (glm::vec3& p : mesh.positions) {
        glm::vec3 d = p - centre;
        d = glm::vec3(d.x, c * d.y - c * d.z, c * d.y + c * d.z);
        d = glm::vec3(c * d.x + c * d.z, d.y, -c * d.x + c * d.z);
        p = centre + d;
    }
    return mesh;
}

TestGltf occludedFurnace(glm::vec3 sigmaS) {
    TestGltf g = furnace(glm::vec3(kRho));
    g.materials.push_back(vkdrMediumMaterial("smoke", glm::vec3(0.0f), sigmaS, 0.3f));
    g.meshes.push_back(turnedBox(glm::vec3(-0.5f, -0.6f, 0.0f), glm::vec3(0.4f, 0.2f, 0.8f), 1));
    g.meshes.push_back(turnedBox(glm::vec3(-0.2f, -0.4f, 0.2f), glm::vec3(0.1f, 0.0f, 0.6f), 0));
    g.meshes.push_back(turnedBox(glm::vec3(-0.9f, 0.45f, 0.1f), glm::vec3(-0.4f, 0.85f, 0.6f), 0));
    return g;
}

class ShadowRayTest : public RenderTest {};

// An empty medium (sigma = 0) leaves only visibility to get right.
TEST_F(ShadowRayTest, DirectLightStopsAtTheFirstOpaqueHitWithinTheLight) {
    auto file = occludedFurnace(glm::vec3(0.0f)).write(tempDir(), "furnace");
    Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = 32, .maxDepth = 1});
    expectUniformRadiance(image, glm::dvec3(kFurnaceLe) * (1.0 + kRho));
}

TEST_F(ShadowRayTest, TransmittanceThroughAScatteringMediumWithOpaqueSurfacesInside) {
    auto file = occludedFurnace(glm::vec3(0.5f, 1.0f, 2.0f)).write(tempDir(), "furnace");
    Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = 32, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kFurnaceLe) / (1.0 - kRho));
}

}  // namespace
}  // namespace vkdr::test
