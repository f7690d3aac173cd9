// Which parameter bench differentiates (sigma_s of the first medium, sigma_a where that
// is 0 or has no gradient, nothing without a medium that has either), and that its
// gradient, taken at half the target's value, is clearly not 0.
#include <cmath>

#include <gtest/gtest.h>

#include "bench/bench_scene.h"
#include "bench/gradient_benchmark.h"
#include "bvh/bvh.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace vkdr::test {
namespace {

Scene sceneWithMedia(std::vector<Medium> media) {
    Scene scene;
    scene.media = std::move(media);
    return scene;
}

TEST(BenchGradientParameter, ScatteringOfTheFirstMedium) {
    Scene scene = sceneWithMedia({{"fog", glm::vec3(0.01f), glm::vec3(0.0f, 0.0f, 0.04f), 0.0f},
                                  {"smoke", glm::vec3(0.05f), glm::vec3(4.0f), 0.3f}});
    EXPECT_EQ(benchGradientParameter(scene), "media/fog/sigma_s");
}

TEST(BenchGradientParameter, AbsorptionWhereTheMediumDoesNotScatter) {
    Scene scene = sceneWithMedia({{"ink", glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(0.0f), 0.0f}});
    EXPECT_EQ(benchGradientParameter(scene), "media/ink/sigma_a");
}

// The adjoint has no gradient for a density grid's sigma_s with a channel at 0.
TEST(BenchGradientParameter, AbsorptionOfAGridThatDoesNotScatterInAChannel) {
    Medium plume{"plume", glm::vec3(0.5f), glm::vec3(1.0f, 1.0f, 0.0f), 0.0f};
    plume.densityGrid = 0;
    EXPECT_EQ(benchGradientParameter(sceneWithMedia({plume})), "media/plume/sigma_a");
    plume.sigma_s = glm::vec3(1.0f, 1.0f, 0.5f);
    EXPECT_EQ(benchGradientParameter(sceneWithMedia({plume})), "media/plume/sigma_s");
}

TEST(BenchGradientParameter, NoneWithoutAMediumThatScattersOrAbsorbs) {
    EXPECT_EQ(benchGradientParameter(Scene{}), std::nullopt);
    Scene vacuum = sceneWithMedia({{"vacuum", glm::vec3(0.0f), glm::vec3(0.0f), 0.0f},
                                   {"fog", glm::vec3(0.01f), glm::vec3(0.04f), 0.0f}});
    EXPECT_EQ(benchGradientParameter(vacuum), std::nullopt);
}

TEST(BenchGradientParameter, OfTheShippedScenes) {
    auto parameterOf = [](const char* name) {
        return benchGradientParameter(loadBenchScene(resolveBenchScene(name, VKDR_TEST_SCENES_DIR)).scene);
    };
    EXPECT_EQ(parameterOf("cornell_fog"), "media/fog/sigma_s");
    EXPECT_EQ(parameterOf("cornell_smoke"), "media/smoke/sigma_s");
    EXPECT_EQ(parameterOf("cornell_box"), std::nullopt);
    EXPECT_EQ(parameterOf("room_2k"), "media/fog/sigma_s");
}

TEST(BenchmarkGradient, PointsFromHalfTheValueBackToTheTargets) {
    // Where each pixel's expected value is monotonic in sigma_s between half its value and
    // its value, every pixel's part of the expected L2 gradient at half the value,
    // (E[I] - T) dE[I]/dsigma_s, is negative. 32x32 at 16 spp: one estimate's relative
    // noise is at most about 0.5 (docs/performance.md's 64x64 at 16 spp gave 0.08), so
    // the mean of 6 is at least about 5 standard errors from 0; asked for: more than 2.
    VulkanContext context(ContextOptions{});
    Scene scene = loadBenchScene(resolveBenchScene("cornell_fog", VKDR_TEST_SCENES_DIR)).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings;
    settings.width = 32;
    settings.height = 32;
    settings.spp = 16;
    settings.maxDepth = 3;
    settings.seed = 1;
    const Image target = Renderer(context, scene, bvh, settings).render();
    int evaluations = 0;
    std::optional<GradientBenchmark> gradient =
        benchmarkGradient(context, scene, bvh, target, settings, 6, [&] { ++evaluations; });
    EXPECT_EQ(evaluations, 6);
    ASSERT_TRUE(gradient.has_value());
    EXPECT_EQ(gradient->parameter, "media/fog/sigma_s");
    ASSERT_TRUE(gradient->noise.has_value());
    EXPECT_LT(gradient->noise->mean, -2.0 * gradient->noise->standardError);
    ASSERT_TRUE(gradient->noise->relativeNoise.has_value());
    ASSERT_TRUE(gradient->efficiency().has_value());
    EXPECT_TRUE(std::isfinite(*gradient->efficiency()));
    requireNoValidationMessages(context);
}

}  // namespace
}  // namespace vkdr::test
