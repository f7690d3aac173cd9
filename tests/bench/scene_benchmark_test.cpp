// One scene benchmarked at a tiny size: every figure is there, and the stage times
// come from the timestamps of every stage (their values are not judged: this is a
// benchmark, not a test of speed).
#include <gtest/gtest.h>

#include "bench/bench_scene.h"
#include "bench/scene_benchmark.h"
#include "vk/context.h"

namespace vkdr::test {
namespace {

TEST(SceneBenchmark, ReportsEveryStageOfATinyRender) {
    VulkanContext context(ContextOptions{});
    Scene scene = loadBenchScene(resolveBenchScene("cornell_fog", VKDR_TEST_SCENES_DIR));
    BenchSettings settings;
    settings.render.width = 8;
    settings.render.height = 6;
    settings.render.spp = 2;
    settings.render.maxDepth = 3;
    settings.iterations = 2;  // two forward passes at two seeds: the noise figure
    double lastProgress = 0.0;
    SceneBenchmark result = benchmarkScene(context, "cornell_fog", scene, settings, [&](double fraction) {
        EXPECT_GE(fraction, lastProgress);
        lastProgress = fraction;
    });
    EXPECT_DOUBLE_EQ(lastProgress, 1.0);

    EXPECT_EQ(result.triangles, scene.triangles.size());
    EXPECT_EQ(result.width, 8);
    EXPECT_EQ(result.height, 6);
    EXPECT_EQ(result.paths, 8u * 6u * 2u);
    EXPECT_GT(result.rays, result.paths);
    EXPECT_GT(result.forwardMs, 0.0);
    EXPECT_GT(result.gradientMs, 0.0);
    ASSERT_TRUE(result.relativeNoise.has_value());
    EXPECT_GT(*result.relativeNoise, 0.0);
    EXPECT_GT(result.efficiency(), 0.0);
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
    requireNoValidationMessages(context);
}

}  // namespace
}  // namespace vkdr::test
