// Views of one image size share a renderer: Renderer::setCamera moves it to another
// camera, and the gradients of several views add up in one sum on the device
// (Renderer::renderAddingGradients), read back once.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "diff/rendered_loss_gradient.h"
#include "gradient_scenes.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

// The smoke room with a second camera inside the smoke box, looking across it.
Scene smokeRoomWithCameraInTheSmoke(const std::filesystem::path& dir) {
    TestGltf gltf = smokeRoom();
    gltf.moreCameras.push_back({"in_smoke", glm::vec3(0.0f, -0.5f, 0.2f), glm::vec3(-1.0f, -0.2f, 0.3f)});
    return loadScene(gltf.write(dir, "scene")).scene;
}

Image flatImage(int side, float value) {
    return {side, side, std::vector<float>(size_t(side) * side * 3, value)};
}

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

const RenderSettings kSettings{.width = 16, .height = 16, .spp = 8, .maxDepth = 5};

TEST_F(RenderTest, SetCameraRendersWhatARendererBuiltForThatCameraRenders) {
    const Scene scene = smokeRoomWithCameraInTheSmoke(tempDir());
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Renderer moved(testContext(), scene, bvh, kSettings);
    moved.setCamera(scene, "in_smoke");
    RenderSettings inSmoke = kSettings;
    inSmoke.camera = "in_smoke";
    Renderer built(testContext(), scene, bvh, inSmoke);
    const Image a = moved.render(), b = built.render();
    EXPECT_TRUE(sameBits(a, b));
    EXPECT_FALSE(sameBits(a, Renderer(testContext(), scene, bvh, kSettings).render()));
    EXPECT_THROW(moved.setCamera(scene, "no_such_camera"), Error);
}

// The sum of two views' gradients read back once equals the two read back one by one,
// up to the rounding of each read-back to a float: the device's fixed-point sums are
// exact, and each rounding errs by at most 2^-24 of its value, so the two differ by at
// most 2^-24 (|a + b| + |a| + |b|) <= 2^-23 (|a| + |b|); the test allows 2^-22.
TEST_F(RenderTest, GradientsOfTwoViewsAddUpInOneSum) {
    const Scene scene = smokeRoomWithCameraInTheSmoke(tempDir());
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Renderer renderer(testContext(), scene, bvh, kSettings);
    const Image targetA = flatImage(16, 0.2f), targetB = flatImage(16, 0.05f);
    renderer.enableGradients(targetA, LossKind::L2);
    const auto pointAt = [&](const std::string& camera, const Image& target, uint32_t seed) {
        renderer.setCamera(scene, camera);
        renderer.setTarget(target);
        renderer.setSeed(seed);
    };

    renderer.clearGradientSum();
    pointAt("", targetA, 1);
    const GradientEvaluation addedA = renderer.renderAddingGradients();
    pointAt("in_smoke", targetB, 2);
    const GradientEvaluation addedB = renderer.renderAddingGradients();
    const SceneGradients sum = renderer.downloadGradientSum();

    pointAt("", targetA, 1);
    const GradientEvaluation alone = renderer.renderWithGradients();
    pointAt("in_smoke", targetB, 2);
    const GradientEvaluation aloneB = renderer.renderWithGradients();

    EXPECT_TRUE(sameBits(addedA.image, alone.image));
    EXPECT_TRUE(sameBits(addedB.image, aloneB.image));
    EXPECT_TRUE(sameBits(addedA.loss, alone.loss));
    EXPECT_TRUE(sameBits(addedB.loss, aloneB.loss));
    EXPECT_TRUE(addedA.gradients.media.empty()) << "a view adding to the sum reads no gradients back";
    ASSERT_EQ(sum.media.size(), alone.gradients.media.size());
    int nonZero = 0;
    for (size_t i = 0; i < sum.media.size(); ++i) {
        const double a = alone.gradients.media[i], b = aloneB.gradients.media[i];
        EXPECT_NEAR(sum.media[i], a + b, std::ldexp(std::abs(a) + std::abs(b), -22)) << "media[" << i << "]";
        nonZero += a != 0.0 && b != 0.0;
    }
    EXPECT_GT(nonZero, 0) << "both views see the smoke";
}

// Views of two sizes: each image comes back in its view's place, rendered as a renderer
// of its own for that view renders it with the view's seed, and the gradient is the mean
// of those renderers' gradients; the loss evaluate() returns is the one loss() renders
// with the same random numbers (up to the order of the sum over views).
TEST_F(RenderTest, ViewsOfSeveralSizesComeBackInOrder) {
    const Scene scene = smokeRoomWithCameraInTheSmoke(tempDir());
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    std::vector<TargetView> views = {{"", flatImage(16, 0.2f)}, {"in_smoke", flatImage(12, 0.1f)},
                                     {"in_smoke", flatImage(16, 0.1f)}};
    const RenderSettings settings{.spp = 4, .maxDepth = 5};
    RenderedLossGradient lossGradient(testContext(), scene, views, {"media/smoke/sigma_s"}, settings, LossKind::L2);
    const GradientResult result = lossGradient.evaluate(scene, 7);
    ASSERT_EQ(result.images.size(), 3u);
    ASSERT_EQ(result.parameters.size(), 1u);
    const size_t smoke = size_t(std::find_if(scene.media.begin(), scene.media.end(),
                                             [](const Medium& m) { return m.name == "smoke"; }) -
                                scene.media.begin());
    ASSERT_LT(smoke, scene.media.size());
    // Each view's gradient, and the shared sum, are rounded to float once: 2^-23 of the
    // terms' magnitudes bounds the difference (above); the test allows 2^-21.
    std::vector<double> mean(3, 0.0), bound(3, 0.0);
    for (size_t v = 0; v < views.size(); ++v) {
        RenderSettings own = settings;
        own.camera = views[v].camera;
        own.width = uint32_t(views[v].target.width);
        own.height = uint32_t(views[v].target.height);
        Renderer renderer(testContext(), scene, bvh, own);
        renderer.enableGradients(views[v].target, LossKind::L2);
        renderer.setSeed(viewSeed(7, v));
        const GradientEvaluation alone = renderer.renderWithGradients();
        EXPECT_TRUE(sameBits(result.images[v], alone.image)) << "view " << v;
        for (int c = 0; c < 3; ++c) {
            const double g =
                alone.gradients.media[smoke * gpu::kMediumGradientStride + gpu::kMediumGradientSigmaS + size_t(c)] / 3.0;
            mean[c] += g;
            bound[c] += std::ldexp(std::abs(g), -21);
        }
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(result.parameters[0].gradient[c], mean[c], bound[c]) << "channel " << c;
    }
    const double loss = lossGradient.loss(scene, 7);
    EXPECT_NEAR(result.loss, loss, 1e-12 * loss);
}

}  // namespace
}  // namespace vkdr::test
