// Gradients and the loss repeat bit for bit: the device adds them as fixed-point sums
// (shaders/lib/fixed_point.glsl), whose total does not depend on the order in which
// lavapipe's threads, or a GPU's subgroups, arrive. With float atomics three evaluations
// in a row gave three different bit patterns.
#include <cstring>
#include <filesystem>

#include "diff/rendered_loss_gradient.h"
#include "gradient_scenes.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// The foggy room with a texture on its walls.
Scene texturedFoggyRoom(const std::filesystem::path& dir) {
    Scene scene = loadScene(foggyRoom().write(dir, "scene")).scene;
    scene.textures.push_back({"stripes", 2, 1, {glm::vec4(0.8f, 0.5f, 0.3f, 1.0f), glm::vec4(0.4f, 0.7f, 0.6f, 1.0f)}});
    scene.materials[0].baseColorTexture = 0;
    scene.uvs.clear();
    for (const glm::vec3& p : scene.positions) {
        scene.uvs.push_back(glm::vec2(p.x + p.y, p.y - p.z));
    }
    return scene;
}

// A parameter of every kind the room has (all but a punctual light's intensity).
const std::vector<std::string> kEveryKind = {"media/fog/sigma_a", "media/fog/sigma_s", "media/fog/g",
                                             "materials/walls/base_color", "materials/walls/base_color_texture",
                                             "lights/lamp/emission"};

Image greyImage(int side) {
    return {side, side, std::vector<float>(size_t(side) * side * 3, 0.3f)};
}

TEST_F(RenderTest, GradientsAndLossRepeatBitForBit) {
    const Scene scene = texturedFoggyRoom(tempDir());
    const std::vector<std::string>& names = kEveryKind;
    RenderedLossGradient lossGradient(testContext(), scene, {{"", greyImage(48)}}, names,
                                      {.spp = 16, .maxDepth = 6}, LossKind::L2);
    const GradientResult first = lossGradient.evaluate(scene, 3);
    for (int repeat = 0; repeat < 3; ++repeat) {
        const GradientResult again = lossGradient.evaluate(scene, 3);
        EXPECT_TRUE(sameBits(first.loss, again.loss)) << first.loss << " then " << again.loss;
        for (size_t p = 0; p < names.size(); ++p) {
            for (size_t c = 0; c < first.parameters[p].gradient.size(); ++c) {
                const double a = first.parameters[p].gradient[c], b = again.parameters[p].gradient[c];
                EXPECT_NE(a, 0.0) << names[p] << "[" << c << "]";
                EXPECT_TRUE(sameBits(a, b)) << names[p] << "[" << c << "]: " << a << " then " << b;
            }
        }
    }
}

// The adjoint stages are compiled for the kinds of gradient asked for alone
// (DerivativeTargets): each gradient asked for by itself has the bits it has among all.
// (The fog scatters: one that did not would be sampled only by a pass that wants sigma_s.)
TEST_F(RenderTest, AGradientAskedForAloneHasTheBitsItHasAmongAll) {
    const Scene scene = texturedFoggyRoom(tempDir());
    const RenderSettings settings{.spp = 8, .maxDepth = 4};
    RenderedLossGradient every(testContext(), scene, {{"", greyImage(24)}}, kEveryKind, settings, LossKind::L2);
    const GradientResult all = every.evaluate(scene, 5);
    for (size_t p = 0; p < kEveryKind.size(); ++p) {
        RenderedLossGradient one(testContext(), scene, {{"", greyImage(24)}}, {kEveryKind[p]}, settings, LossKind::L2);
        const GradientResult alone = one.evaluate(scene, 5);
        EXPECT_TRUE(sameBits(alone.loss, all.loss)) << kEveryKind[p];
        ASSERT_EQ(alone.parameters[0].gradient.size(), all.parameters[p].gradient.size());
        for (size_t c = 0; c < alone.parameters[0].gradient.size(); ++c) {
            const double a = alone.parameters[0].gradient[c], b = all.parameters[p].gradient[c];
            EXPECT_NE(b, 0.0) << kEveryKind[p] << "[" << c << "]";
            EXPECT_TRUE(sameBits(a, b)) << kEveryKind[p] << "[" << c << "]: " << a << " alone, " << b << " among all";
        }
    }
}

}  // namespace
}  // namespace vkdr::test
