// The gradient at a few samples per pixel. dLoss/dI and the adjoint come from different
// samples (split halves, or at one sample an independent replay), so the gradient of a
// squared loss is unbiased however few the samples: its mean over many seeds must match
// the mean at 64 samples within five combined standard errors. An estimator that took
// both from the same samples would be off by 2 Cov(I, dI/dtheta) / spp, several times
// the tolerance here. Keeping half of the paths' radiance must give the same gradient as
// rendering them again, whatever the passes look like.
#include <cmath>

#include "bvh/bvh.h"
#include "diff/gradient_over_seeds.h"
#include "diff/rendered_loss_gradient.h"
#include "gradient_scenes.h"
#include "render/renderer.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
const std::vector<std::string> kParameters = {"lights/lamp/emission", "media/fog/sigma_s"};

class SplitSamplesTest : public RenderTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(SplitSamplesTest, FewSamplesPerPixelGiveTheSameMeanGradient) {
    const uint32_t spp = GetParam();
    Scene scene = loadScene(foggyRoom().write(tempDir(), "fog")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    auto meanGradient = [&](uint32_t samples, uint32_t seeds, uint32_t firstSeed) {
        RenderedLossGradient lg(testContext(), scene, {{"", black}}, kParameters,
                                {.spp = samples, .maxDepth = 4}, LossKind::L2);
        return gradientOverSeeds(lg, scene, seeds, firstSeed);
    };
    // Equal total samples on both sides; distinct seeds keep the two means independent.
    const auto reference = meanGradient(64, 8, 0);
    const auto few = meanGradient(spp, 512 / spp, 1000);
    for (size_t p = 0; p < kParameters.size(); ++p) {
        for (size_t c = 0; c < 3; ++c) {
            const MeanAndError& r = reference[p][c];
            const MeanAndError& f = few[p][c];
            EXPECT_NEAR(f.mean, r.mean, 5.0 * std::hypot(f.error, r.error))
                << kParameters[p] << "[" << c << "] at " << spp << " spp: " << f.mean << " +- " << f.error
                << ", at 64 spp " << r.mean << " +- " << r.error;
            EXPECT_GT(std::abs(r.mean), 5.0 * r.error) << kParameters[p] << "[" << c << "]";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(SamplesPerPixel, SplitSamplesTest, ::testing::Values(1u, 2u, 3u));

GradientEvaluation evaluate(const Scene& scene, const Bvh& bvh, const RenderSettings& settings) {
    Renderer renderer(testContext(), scene, bvh, settings);
    renderer.enableGradients(Image{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)}, LossKind::L2);
    renderer.setSeed(3);
    return renderer.renderWithGradients();
}

// Equal but for float rounding: relative 1e-4, a few hundred ulps, is far below any
// change of estimator, which moves a gradient of these few paths by percents.
void expectClose(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
    ASSERT_EQ(a.size(), b.size());
    float largest = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i], b[i], 1e-4f * std::max(std::abs(a[i]), std::abs(b[i])) + 1e-9f) << what << "[" << i << "]";
        largest = std::max(largest, std::abs(a[i]));
    }
    EXPECT_GT(largest, 0.0f) << what;
}

// Passes of part of the pixels (20 paths) and of several samples of every pixel (150).
class KeptRadianceTest : public RenderTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(KeptRadianceTest, MatchesRenderingThePathsAgain) {
    Scene scene = loadScene(foggyRoom().write(tempDir(), "fog")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings{.width = kSide, .height = kSide, .spp = 7, .maxDepth = 4, .pathsPerPass = GetParam()};
    const GradientEvaluation kept = evaluate(scene, bvh, settings);
    settings.keptRadianceBytes = 0;
    const GradientEvaluation replayed = evaluate(scene, bvh, settings);

    EXPECT_EQ(kept.image.rgb, replayed.image.rgb);
    EXPECT_EQ(kept.loss, replayed.loss);
    // The same paths, differentiated at the same images: only the order of the float
    // atomic adds differs.
    expectClose(kept.gradients.media, replayed.gradients.media, "media");
    expectClose(kept.gradients.emissions, replayed.gradients.emissions, "emissions");
    expectClose(kept.gradients.baseColors, replayed.gradients.baseColors, "base colours");
}

INSTANTIATE_TEST_SUITE_P(PathsPerPass, KeptRadianceTest, ::testing::Values(20u, 150u));

// When every path fits in one pass, both halves render in it and one adjoint pass
// follows them all; a pass one path short of that takes the four passes of the split
// halves. The same paths at the same images: only float rounding may differ (the film
// sums its samples in another grouping, and the atomic adds come in another order).
TEST_F(RenderTest, OnePassGivesTheGradientOfFourPasses) {
    Scene scene = loadScene(foggyRoom().write(tempDir(), "fog")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings{.width = kSide, .height = kSide, .spp = 7, .maxDepth = 4};
    const GradientEvaluation onePass = evaluate(scene, bvh, settings);
    settings.pathsPerPass = kSide * kSide * settings.spp - 1;
    const GradientEvaluation fourPasses = evaluate(scene, bvh, settings);

    expectClose(onePass.image.rgb, fourPasses.image.rgb, "image");
    EXPECT_NEAR(onePass.loss, fourPasses.loss, 1e-5 * std::abs(fourPasses.loss));
    expectClose(onePass.gradients.media, fourPasses.gradients.media, "media");
    expectClose(onePass.gradients.emissions, fourPasses.gradients.emissions, "emissions");
    expectClose(onePass.gradients.baseColors, fourPasses.gradients.baseColors, "base colours");
}

}  // namespace
}  // namespace vkdr::test
