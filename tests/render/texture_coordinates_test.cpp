// Texture coordinates anywhere in float's range are valid glTF. The lookup wraps them
// (repeat) without leaving the texture: a shift by whole periods renders the same image,
// and coordinates so far from [0, 1) that float holds only whole periods there look up
// the texture at its corner, as (0, 0) would, instead of reading outside the texels.
#include "render_test_support.h"
#include "bvh/bvh.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

const glm::vec4 kStripeA(0.8f, 0.5f, 0.3f, 1.0f), kStripeB(0.1f, 0.7f, 0.6f, 1.0f);

class TextureCoordinatesTest : public RenderTest {
protected:
    // A box of glowing walls, seen from inside, whose base colour is a two-texel texture
    // (by default a stripe) repeated across every face, with texture coordinates shifted
    // by `offset`.
    Image render(float offset, std::vector<glm::vec4> texels = {kStripeA, kStripeB}) {
        TestGltf g;
        g.materials = {emissiveMaterial("walls", glm::vec3(1.0f, 0.8f, 0.6f), true)};
        g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0)};
        g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
        Scene scene = loadScene(g.write(tempDir(), "scene")).scene;
        scene.textures.push_back({"stripes", 2, 1, std::move(texels)});
        scene.materials[0].baseColorTexture = 0;
        scene.uvs.clear();
        for (const glm::vec3& p : scene.positions) {
            scene.uvs.push_back(glm::vec2(p.x + p.y + p.z, p.y - p.z) * 0.75f + offset);
        }
        Bvh bvh = buildBvh(scene.positions, scene.triangles);
        // Direct light only: no Russian roulette, whose decisions a last-bit change in a
        // texel weight could flip.
        return Renderer(testContext(), scene, bvh, {.width = 16, .height = 12, .spp = 8, .maxDepth = 1}).render();
    }
};

TEST_F(TextureCoordinatesTest, AShiftByWholePeriodsRendersTheSameImage) {
    const Image unshifted = render(0.0f);
    ASSERT_TRUE(allFinite(unshifted));
    for (float offset : {3.0f, -5.0f}) {
        const Image shifted = render(offset);
        ASSERT_EQ(shifted.rgb.size(), unshifted.rgb.size());
        // The shift rounds a coordinate near 2 by up to half an ulp of 7, 5e-7 of a
        // period: a texel weight, and so a pixel, changes by about that much at most.
        for (size_t i = 0; i < unshifted.rgb.size(); ++i) {
            EXPECT_NEAR(shifted.rgb[i], unshifted.rgb[i], 1e-5f * std::max(unshifted.rgb[i], 1.0f))
                << "offset " << offset << ", value " << i;
        }
    }
}

TEST_F(TextureCoordinatesTest, CoordinatesOfWholePeriodsOnlyLookUpTheCorner) {
    // At a coordinate of whole periods a bilinear lookup blends the two texels half and
    // half: the image of a texture of their mean everywhere.
    const glm::vec4 mean = 0.5f * (kStripeA + kStripeB);
    const Image expected = render(0.0f, {mean, mean});
    ASSERT_TRUE(allFinite(expected));
    // Float spaces values 64 apart at 1e9, 1024 at 1e10 and 2e31 at 3e38.
    for (float offset : {1e9f, -1e10f, 3e38f}) {
        const Image far = render(offset);
        ASSERT_EQ(far.rgb.size(), expected.rgb.size());
        for (size_t i = 0; i < expected.rgb.size(); ++i) {
            EXPECT_NEAR(far.rgb[i], expected.rgb[i], 1e-5f * std::max(expected.rgb[i], 1.0f))
                << "offset " << offset << ", value " << i;
        }
    }
}

}  // namespace
}  // namespace vkdr::test
