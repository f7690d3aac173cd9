// The benchmark's JSON has the shape issue 4 asks for, and the table a row per scene.
#include <gtest/gtest.h>

#include "bench/bench_report.h"

namespace vkdr::test {
namespace {

BenchReport exampleReport() {
    SceneBenchmark scene;
    scene.name = "room_10k";
    scene.triangles = 10012;
    scene.width = 16;
    scene.height = 12;
    scene.spp = 2;
    scene.maxDepth = 4;
    scene.bvhBuildMs = 5.0;
    scene.forwardMs = 100.0;
    scene.gradientMs = 250.0;
    scene.paths = 384;
    scene.rays = 1000;
    scene.relativeNoise = 0.5;
    scene.stagesMs = {{"generate", 1.0}, {"intersect", 2.0}, {"adjoint", 3.0}};
    scene.adjointStagesMs = {{"shade", 1.5}};
    scene.peakAllocatedDeviceBytes = 1 << 20;
    scene.peakHostBytes = 1 << 24;
    scene.gradient = GradientBenchmark{"media/fog/sigma_s", 8, 200.0, GradientNoise{-2.0, 0.25, 0.5}};
    BenchReport report{"llvmpipe", "Mesa", 3, {scene}, {{"room_10m", "needs about 5 GiB of host memory"}}};
    return report;
}

TEST(BenchReport, JsonHasEveryFieldOfTheIssue) {
    nlohmann::ordered_json json = reportJson(exampleReport());
    EXPECT_EQ(json["device"], "llvmpipe");
    EXPECT_EQ(json["driver"], "Mesa");
    ASSERT_EQ(json["scenes"].size(), 1u);
    const auto& scene = json["scenes"][0];
    for (const char* key : {"name", "triangles", "width", "height", "spp", "max_depth", "bvh_build_ms", "stages_ms",
                            "forward_ms", "gradient_ms", "gradient_to_forward", "paths_per_s", "rays_per_s",
                            "relative_noise", "efficiency", "gradient_parameter", "gradient_seeds", "gradient_mean",
                            "gradient_standard_error", "gradient_relative_noise", "gradient_evaluation_ms",
                            "gradient_efficiency", "peak_device_bytes", "peak_host_bytes"}) {
        EXPECT_TRUE(scene.contains(key)) << key;
    }
    for (const char* stage : {"generate", "intersect", "medium_sample", "shade", "shadow", "loss", "adjoint"}) {
        EXPECT_TRUE(scene["stages_ms"].contains(stage)) << stage;
    }
    EXPECT_EQ(scene["triangles"], 10012);
    EXPECT_EQ(scene["stages_ms"]["intersect"], 2.0);
    EXPECT_EQ(scene["stages_ms"]["shadow"], 0.0);  // not measured: 0, never missing
    EXPECT_DOUBLE_EQ(scene["gradient_to_forward"].get<double>(), 2.5);
    EXPECT_DOUBLE_EQ(scene["paths_per_s"].get<double>(), 3840.0);
    EXPECT_DOUBLE_EQ(scene["efficiency"].get<double>(), 1.0 / (0.25 * 0.1));
    EXPECT_DOUBLE_EQ(scene["bvh_triangles_per_s"].get<double>(), 10012.0 / 0.005);
    EXPECT_EQ(scene["peak_device_bytes"], 1 << 20);
    EXPECT_EQ(scene["peak_device_source"], "allocations");
    EXPECT_EQ(json["skipped"][0]["name"], "room_10m");
    EXPECT_EQ(scene["gradient_parameter"], "media/fog/sigma_s");
    EXPECT_EQ(scene["gradient_seeds"], 8);
    EXPECT_EQ(scene["gradient_mean"], -2.0);
    EXPECT_EQ(scene["gradient_standard_error"], 0.25);
    EXPECT_EQ(scene["gradient_relative_noise"], 0.5);
    EXPECT_EQ(scene["gradient_evaluation_ms"], 200.0);
    EXPECT_DOUBLE_EQ(scene["gradient_efficiency"].get<double>(), 1.0 / (0.25 * 0.2));
}

TEST(BenchReport, GradientFiguresAreNullWhereThereAreNone) {
    BenchReport report = exampleReport();
    report.scenes.push_back(report.scenes[0]);
    report.scenes[0].gradient.reset();                            // no medium
    report.scenes[1].gradient->noise.reset();                     // one seed
    nlohmann::ordered_json json = reportJson(report);
    for (const char* key : {"gradient_parameter", "gradient_seeds", "gradient_mean", "gradient_standard_error",
                            "gradient_relative_noise", "gradient_evaluation_ms", "gradient_efficiency"}) {
        EXPECT_TRUE(json["scenes"][0][key].is_null()) << key;
    }
    EXPECT_EQ(json["scenes"][1]["gradient_parameter"], "media/fog/sigma_s");
    EXPECT_EQ(json["scenes"][1]["gradient_evaluation_ms"], 200.0);
    for (const char* key : {"gradient_mean", "gradient_standard_error", "gradient_relative_noise",
                            "gradient_efficiency"}) {
        EXPECT_TRUE(json["scenes"][1][key].is_null()) << key;
    }
    std::string table = markdownTable(report);
    EXPECT_NE(table.find("| 0.5000 | 40 | - | - | 1.0 | 16.0 |\n"), std::string::npos) << table;
    EXPECT_NE(table.find("| room_10k | - | - | - | - | - |\n"), std::string::npos) << table;
    EXPECT_NE(table.find("| room_10k | media/fog/sigma_s | 8 | - | - | 200.0 |\n"), std::string::npos) << table;
}

// A black image has no relative noise, and so no efficiency, which is defined by it.
TEST(BenchReport, ImageEfficiencyIsNullWithoutRelativeNoise) {
    BenchReport report = exampleReport();
    report.scenes[0].relativeNoise.reset();
    nlohmann::ordered_json json = reportJson(report);
    EXPECT_TRUE(json["scenes"][0]["relative_noise"].is_null());
    EXPECT_TRUE(json["scenes"][0]["efficiency"].is_null());
}

TEST(BenchReport, DensityGridFiguresAreNullWithoutGrids) {
    BenchReport report = exampleReport();
    EXPECT_EQ(markdownTable(report).find("Density grids"), std::string::npos);  // no grid, no table
    report.scenes.push_back(report.scenes[0]);
    report.scenes[1].name = "plume_64";
    report.scenes[1].densityGrids = DensityGridFigures{262144, 12345, 7.25};
    report.scenes[1].densityGradient = DensityGradientTimes{110.0, 220.0};
    nlohmann::ordered_json json = reportJson(report);
    for (const char* key :
         {"grid_voxels", "active_voxels", "majorant_build_ms", "density_gradient_ms", "density_forward_ms",
          "density_gradient_to_forward"}) {
        EXPECT_TRUE(json["scenes"][0][key].is_null()) << key;
    }
    EXPECT_EQ(json["scenes"][1]["grid_voxels"], 262144);
    EXPECT_EQ(json["scenes"][1]["active_voxels"], 12345);
    EXPECT_EQ(json["scenes"][1]["majorant_build_ms"], 7.25);
    EXPECT_EQ(json["scenes"][1]["density_gradient_ms"], 220.0);
    EXPECT_EQ(json["scenes"][1]["density_forward_ms"], 110.0);
    // Against the forward passes timed in turn with it, not the scene's forward_ms (100).
    EXPECT_DOUBLE_EQ(json["scenes"][1]["density_gradient_to_forward"].get<double>(), 2.0);
    std::string table = markdownTable(report);
    EXPECT_NE(table.find("| scene | grid voxels | active voxels | majorant build ms | density gradient ms | "
                         "forward ms, in turn | density gradient/forward |\n"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("| room_10k | - | - | - | - | - | - |\n"), std::string::npos) << table;
    EXPECT_NE(table.find("| plume_64 | 262144 | 12345 | 7.25 | 220.0 | 110.0 | 2.00 |\n"), std::string::npos) << table;
}

TEST(BenchReport, DriverMemoryCountTakesPrecedence) {
    BenchReport report = exampleReport();
    report.scenes[0].peakDriverDeviceBytes = 3 << 20;
    nlohmann::ordered_json json = reportJson(report);
    const auto& scene = json["scenes"][0];
    EXPECT_EQ(scene["peak_device_bytes"], 3 << 20);
    EXPECT_EQ(scene["peak_device_source"], "VK_EXT_memory_budget");
    EXPECT_EQ(scene["peak_allocated_device_bytes"], 1 << 20);
}

TEST(BenchReport, TableHasARowPerSceneAndNamesSkippedOnes) {
    std::string table = markdownTable(exampleReport());
    EXPECT_NE(table.find("| room_10k | 10012 | 16x12 | 2 | 4 |"), std::string::npos) << table;
    // Image noise and efficiency, then the gradient's, then memory.
    EXPECT_NE(table.find("| 0.5000 | 40 | 0.5000 | 20 | 1.0 | 16.0 |\n"), std::string::npos) << table;
    EXPECT_NE(table.find("| room_10k | media/fog/sigma_s | 8 | -2 | 0.25 | 200.0 |\n"), std::string::npos) << table;
    EXPECT_NE(table.find("skipped room_10m: needs about 5 GiB"), std::string::npos) << table;
}

TEST(BenchReport, TableBreaksTheAdjointDownByStage) {
    std::string table = markdownTable(exampleReport());
    // The primal stage row, then the adjoint stage row with its shade time.
    EXPECT_NE(table.find("| room_10k | 1.00 | 2.00 | 0.00 | 0.00 | 0.00 | 0.00 | 3.00 |"), std::string::npos) << table;
    EXPECT_NE(table.find("| scene | generate | intersect | medium_sample | shade | shadow | queue_prepare |\n"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("| room_10k | 0.00 | 0.00 | 0.00 | 1.50 | 0.00 | 0.00 |\n"), std::string::npos) << table;
}

}  // namespace
}  // namespace vkdr::test
