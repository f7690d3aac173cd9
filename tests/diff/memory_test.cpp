// Path replay keeps memory constant in the path depth: the adjoint pass stores nothing
// per vertex, so rendering and differentiating at max depth 4 and 64 hold the same
// device memory.
#include "bvh/bvh.h"
#include "render/renderer.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

class MemoryTest : public RenderTest {};

TEST_F(MemoryTest, DepthDoesNotChangeDeviceMemory) {
    Scene scene = loadScene(std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf").scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Image target{16, 16, std::vector<float>(16 * 16 * 3, 0.1f)};
    uint64_t bytes[2];
    const uint32_t depths[2] = {4, 64};
    for (int i = 0; i < 2; ++i) {
        Renderer renderer(testContext(), scene, bvh, {.width = 16, .height = 16, .spp = 4, .maxDepth = depths[i]});
        renderer.enableGradients(target, LossKind::L2);
        renderer.renderWithGradients();
        bytes[i] = renderer.pathMemoryBytes();
    }
    EXPECT_GT(bytes[0], 0u);
    EXPECT_EQ(bytes[0], bytes[1]);
}

}  // namespace
}  // namespace vkdr::test
