// One scene benchmarked at a tiny size: every figure is there, the stage times come
// from the timestamps of every stage, and the gradient noise is there exactly where the
// scene has a medium parameter and seeds are asked for (the values are not judged: this
// is a benchmark, not a test of speed).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "bench/bench_scene.h"
#include "bench/scene_benchmark.h"
#include "vk/context.h"

namespace vkdr::test {
namespace {

BenchSettings tinySettings() {
    BenchSettings settings;
    settings.render.width = 8;
    settings.render.height = 6;
    settings.render.spp = 2;
    settings.render.maxDepth = 3;
    settings.iterations = 2;     // two forward passes at two seeds: the noise figure
    settings.gradientSeeds = 3;  // the fewest that give a spread, and one more
    return settings;
}

// Without the gradient noise step, for tests of the other figures.
BenchSettings tinySettingsWithoutGradientNoise() {
    BenchSettings settings = tinySettings();
    settings.gradientSeeds = 0;
    return settings;
}

SceneBenchmark benchmarkShippedScene(const VulkanContext& context, const char* name, const BenchSettings& settings) {
    Scene scene = loadBenchScene(resolveBenchScene(name, VKDR_TEST_SCENES_DIR)).scene;
    double lastProgress = 0.0;
    SceneBenchmark result = benchmarkScene(context, name, scene, settings, [&](double fraction) {
        EXPECT_GE(fraction, lastProgress);
        lastProgress = fraction;
    });
    EXPECT_DOUBLE_EQ(lastProgress, 1.0);
    return result;
}

TEST(SceneBenchmark, ReportsEveryStageOfATinyRender) {
    VulkanContext context(ContextOptions{});
    Scene scene = loadBenchScene(resolveBenchScene("cornell_fog", VKDR_TEST_SCENES_DIR)).scene;
    SceneBenchmark result = benchmarkShippedScene(context, "cornell_fog", tinySettings());

    EXPECT_EQ(result.triangles, scene.triangles.size());
    EXPECT_EQ(result.width, 8);
    EXPECT_EQ(result.height, 6);
    EXPECT_EQ(result.paths, 8u * 6u * 2u);
    EXPECT_GT(result.rays, result.paths);
    EXPECT_GT(result.forwardMs, 0.0);
    EXPECT_GT(result.gradientMs, 0.0);
    ASSERT_TRUE(result.relativeNoise.has_value());
    EXPECT_GT(*result.relativeNoise, 0.0);
    EXPECT_GT(result.efficiency().value_or(0.0), 0.0);
    for (const char* stage : {"generate", "intersect", "medium_sample", "shade", "shadow", "queue_prepare", "film",
                              "loss", "replay", "adjoint"}) {
        ASSERT_TRUE(result.stagesMs.contains(stage)) << stage;
        EXPECT_GE(result.stagesMs.at(stage), 0.0) << stage;
    }
    for (const char* stage : {"generate", "intersect", "medium_sample", "shade", "shadow", "queue_prepare"}) {
        EXPECT_TRUE(result.adjointStagesMs.contains(stage)) << stage;
    }
    EXPECT_GT(result.peakAllocatedDeviceBytes, 0u);
    EXPECT_GT(result.peakHostBytes, 0u);

    ASSERT_TRUE(result.gradient.has_value());
    EXPECT_EQ(result.gradient->parameter, "media/fog/sigma_s");
    EXPECT_EQ(result.gradient->seeds, 3u);
    EXPECT_GT(result.gradient->evaluationMs, 0.0);
    ASSERT_TRUE(result.gradient->noise.has_value());
    EXPECT_TRUE(std::isfinite(result.gradient->noise->mean));
    EXPECT_GT(result.gradient->noise->standardError, 0.0);
    ASSERT_TRUE(result.gradient->noise->relativeNoise.has_value());
    EXPECT_GT(*result.gradient->noise->relativeNoise, 0.0);
    EXPECT_GT(result.gradient->efficiency().value_or(0.0), 0.0);
    requireNoValidationMessages(context);
}

TEST(SceneBenchmark, NoGradientNoiseWithoutAMediumOrSeeds) {
    VulkanContext context(ContextOptions{});
    EXPECT_FALSE(benchmarkShippedScene(context, "cornell_box", tinySettings()).gradient.has_value());
    EXPECT_FALSE(
        benchmarkShippedScene(context, "cornell_fog", tinySettingsWithoutGradientNoise()).gradient.has_value());
    requireNoValidationMessages(context);
}

TEST(SceneBenchmark, CountsTheVoxelsOfAPlumeAndTimesItsMajorantsAndItsDensityAlone) {
    VulkanContext context(ContextOptions{});
    const BenchSettings settings = tinySettingsWithoutGradientNoise();
    SceneBenchmark plume = benchmarkShippedScene(context, "plume_16", settings);
    ASSERT_TRUE(plume.densityGrids.has_value());
    const Scene scene = loadBenchScene(resolveBenchScene("plume_16", VKDR_TEST_SCENES_DIR)).scene;
    const std::vector<float>& values = scene.densityGrids[0].grid.values;
    EXPECT_EQ(plume.densityGrids->voxels, 16u * 16u * 16u);
    EXPECT_EQ(plume.densityGrids->activeVoxels,
              uint64_t(std::count_if(values.begin(), values.end(), [](float v) { return v != 0.0f; })));
    EXPECT_GT(plume.densityGrids->activeVoxels, 0u);
    EXPECT_GE(plume.densityGrids->majorantBuildMs, 0.0);
    ASSERT_TRUE(plume.densityGradient.has_value());  // the density alone, as a grid fit
    EXPECT_GT(plume.densityGradient->gradientMs, 0.0);
    EXPECT_GT(plume.densityGradient->forwardMs, 0.0);
    const SceneBenchmark fog = benchmarkShippedScene(context, "cornell_fog", settings);
    EXPECT_FALSE(fog.densityGrids.has_value());
    EXPECT_FALSE(fog.densityGradient.has_value());
    requireNoValidationMessages(context);
}

// The bytes per voxel that whyTooLarge assumes cover what a plume's voxels take on the
// device, without being a gross overestimate: the peaks of two plumes differ by no more
// than the estimates do.
TEST(SceneBenchmark, PlumeMemoryEstimateCoversTheMeasuredPeak) {
    VulkanContext context(ContextOptions{});
    const BenchSettings settings = tinySettingsWithoutGradientNoise();
    const uint64_t small = benchmarkShippedScene(context, "plume_32", settings).peakAllocatedDeviceBytes;
    const uint64_t large = benchmarkShippedScene(context, "plume_64", settings).peakAllocatedDeviceBytes;
    const uint64_t estimated = estimateBenchMemory(resolveBenchScene("plume_64", VKDR_TEST_SCENES_DIR)).deviceBytes -
                               estimateBenchMemory(resolveBenchScene("plume_32", VKDR_TEST_SCENES_DIR)).deviceBytes;
    ASSERT_GT(large, small);
    EXPECT_LE(large - small, estimated);
    EXPECT_GE(double(large - small), 0.5 * double(estimated));
    requireNoValidationMessages(context);
}

}  // namespace
}  // namespace vkdr::test
