// The same scene, seed and device give the same image bit for bit, whatever order the
// paths finish in; another seed gives another image.
#include "render_test_support.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

class DeterminismTest : public RenderTest {};

TEST_F(DeterminismTest, SameSeedSameBitsOtherSeedOtherImage) {
    TestGltf g;
    g.materials = {emissiveMaterial("walls", glm::vec3(1.0f, 0.8f, 0.6f), true),
                   vkdrMediumMaterial("smoke", glm::vec3(0.1f), glm::vec3(2.0f), 0.4f)};
    g.materials[0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.6, 0.6, 0.6, 1.0};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), box(glm::vec3(-0.5f), glm::vec3(0.5f, 0.5f, 0.9f), 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
    auto file = g.write(tempDir(), "scene");
    // A small pass size makes the render span several passes and queue orders.
    RenderSettings settings{.width = 16, .height = 12, .spp = 8, .maxDepth = 6, .seed = 7, .pathsPerPass = 500};
    Image a = renderFile(file, settings);
    Image b = renderFile(file, settings);
    ASSERT_TRUE(allFinite(a));
    EXPECT_EQ(a.rgb, b.rgb);
    settings.seed = 8;
    Image c = renderFile(file, settings);
    EXPECT_NE(a.rgb, c.rgb);
}

}  // namespace
}  // namespace vkdr::test
