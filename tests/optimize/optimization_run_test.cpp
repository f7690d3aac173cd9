// The files an optimisation writes: present, parseable, and absent after a failure.
#include <algorithm>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../image/scratch_directory.h"
#include "core/error.h"
#include "image/image.h"
#include "optimize/loss_chart.h"
#include "optimize/optimization_run.h"
#include "optimize/parameter_table.h"
#include "optimize/value_summary.h"
#include "quadratic_loss_gradient.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

using nlohmann::json;

const std::filesystem::path kFogScene = std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_fog.gltf";

OptimizationJob fogJob(const std::filesystem::path& directory, uint32_t iterations) {
    OptimizationJob job;
    job.sceneFile = kFogScene;
    job.outputDirectory = directory;
    job.options.parameters = {"media/fog/sigma_a", "media/fog/g"};
    job.options.learningRate = 0.01;
    job.options.iterations = iterations;
    job.targets = {{"", Image{4, 3, std::vector<float>(4 * 3 * 3, 0.05f)}}};
    return job;
}

std::vector<std::string> lines(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::string> result;
    for (std::string line; std::getline(in, line);) result.push_back(line);
    return result;
}

TEST(OptimizationRun, WritesEveryOutputFile) {
    ScratchDirectory scratch;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.3}}});
    std::filesystem::path directory = scratch / "new" / "out";  // created, parents too
    OptimizationReport report = runOptimization(loss, scene, fogJob(directory, 5));

    std::vector<std::string> log = lines(directory / "log.jsonl");
    ASSERT_EQ(log.size(), 5u);
    for (size_t i = 0; i < log.size(); ++i) {
        json line = json::parse(log[i]);
        EXPECT_EQ(line["iteration"], i);
        for (const char* key : {"loss", "parameters", "gradients", "forward_ms", "adjoint_ms", "iteration_ms"}) {
            EXPECT_TRUE(line.contains(key)) << key;
        }
        EXPECT_EQ(line["parameters"]["media/fog/sigma_a"].size(), 3u);
        EXPECT_EQ(line["gradients"]["media/fog/g"].size(), 1u);
        EXPECT_EQ(line["forward_ms"], 1.5);
    }
    EXPECT_EQ(json::parse(log[0])["parameters"]["media/fog/sigma_a"][0], 0.01);  // the file's value, as written

    json params = json::parse(std::ifstream(directory / "params.json"));
    EXPECT_EQ(params["media/fog/g"][0].get<float>(), getParameter(scene, "media/fog/g")[0]);

    Scene written = loadScene(directory / "scene.gltf").scene;
    EXPECT_EQ(getParameter(written, "media/fog/sigma_a"), getParameter(scene, "media/fog/sigma_a"));

    std::string svg = readBytes(directory / "loss.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);

    Image final = readImage(directory / "final.exr");
    EXPECT_EQ(final.width, 4);
    EXPECT_EQ(final.rgb[0], report.result.lastImages[0].rgb[0]);
    EXPECT_TRUE(std::filesystem::is_regular_file(directory / "final.png"));
    EXPECT_EQ(readBytes(directory / "report.html").rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_EQ(report.parameters.size(), 2u);
    EXPECT_EQ(report.parameters[1].fitted, getParameter(scene, "media/fog/g"));
    Image difference = readImage(directory / "diff.png");
    EXPECT_EQ(difference.width, 4);
    EXPECT_EQ(difference.height, 3);
    EXPECT_NEAR(report.largestDifference, std::abs(final.rgb[0] - 0.05f), 1e-7f);
    EXPECT_NEAR(difference.rgb[0], 1.0f, 1e-6f);  // the largest difference is white
}

// A grid's 262144 voxels are summarised in the log, params.json, the table and the
// report, and written in full as the .vdb beside scene.gltf, which loads with them.
TEST(OptimizationRun, SummarisesADensityGridAndWritesItsVoxelsBesideTheScene) {
    ScratchDirectory scratch;
    const std::filesystem::path plumeScene = std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_plume.gltf";
    Scene scene = loadScene(plumeScene).scene;
    const std::string density = "media/plume/density";
    const size_t voxels = getParameter(scene, density).size();
    QuadraticLossGradient loss({{density, std::vector<double>(voxels, 1.0)}});
    OptimizationJob job;
    job.sceneFile = plumeScene;
    job.outputDirectory = scratch / "out";
    job.options.parameters = {density};
    job.options.learningRate = 0.05;
    job.options.iterations = 3;
    job.options.smoothness = 0.5;
    job.targets = {{"", Image{4, 3, std::vector<float>(4 * 3 * 3, 0.05f)}}};
    job.measure = [](const Scene&, uint32_t iteration) { return std::vector<Metric>{{"iteration", double(iteration)}}; };
    OptimizationReport report = runOptimization(loss, scene, job);

    const std::filesystem::path& directory = job.outputDirectory;
    std::vector<std::string> log = lines(directory / "log.jsonl");
    ASSERT_EQ(log.size(), 3u);
    for (size_t i = 0; i < log.size(); ++i) {
        EXPECT_LT(log[i].size(), 1000u);
        json line = json::parse(log[i]);
        EXPECT_EQ(line["parameters"][density]["count"], voxels);
        EXPECT_TRUE(line["gradients"][density].contains("l2_norm"));
        EXPECT_EQ(line["metrics"]["iteration"], double(i));
    }
    // Every voxel starts below its minimum (1; the plume's densest is 0.9), and the
    // smoothness gradient is far smaller than the loss's: Adam's first step moves each by
    // the learning rate towards it, so the second line's mean is the first's plus 0.05.
    const double mean0 = json::parse(log[0])["parameters"][density]["mean"];
    EXPECT_NEAR(json::parse(log[1])["parameters"][density]["mean"], mean0 + 0.05, 1e-4);

    json params = json::parse(std::ifstream(directory / "params.json"));
    EXPECT_EQ(params[density]["count"], voxels);
    EXPECT_NEAR(params[density]["mean"].get<double>(), summarise(getParameter(scene, density)).mean, 1e-9);

    Scene written = loadScene(directory / "scene.gltf").scene;
    EXPECT_EQ(getParameter(written, density), getParameter(scene, density));
    EXPECT_TRUE(std::filesystem::is_regular_file(directory / "scene.materials4.density.vdb"));
    EXPECT_LT(std::filesystem::file_size(directory / "report.html"), 200000u);
    EXPECT_NE(readBytes(directory / "report.html").find("over 262144 values"), std::string::npos);
    EXPECT_NE(readBytes(directory / "report.html").find("class=\"metric\""), std::string::npos);
    EXPECT_NE(parameterTable(report.parameters).find("over 262144 values"), std::string::npos);
    ASSERT_EQ(report.result.lastMetrics.size(), 1u);
    EXPECT_EQ(report.result.lastMetrics[0].value, 2.0);
}

TEST(OptimizationRun, RefusesASmoothnessWeightWithoutADensityGrid) {
    ScratchDirectory scratch;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.3}}});
    OptimizationJob job = fogJob(scratch / "out", 2);
    job.options.smoothness = 1.0;
    EXPECT_THROW(runOptimization(loss, scene, job), Error);
    EXPECT_FALSE(std::filesystem::exists(scratch / "out" / "log.jsonl"));
}

TEST(OptimizationRun, LeavesOnlyTheLogOfGoodIterationsWhenAGradientIsNaN) {
    ScratchDirectory scratch;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.3}}});
    loss.failFrom(2, "media/fog/g");
    EXPECT_THROW(runOptimization(loss, scene, fogJob(scratch.path(), 5)), Error);
    EXPECT_EQ(lines(scratch / "log.jsonl").size(), 2u);
    for (const char* file :
         {"scene.gltf", "params.json", "final.exr", "final.png", "diff.png", "loss.svg", "report.html"}) {
        EXPECT_FALSE(std::filesystem::exists(scratch / file)) << file;
    }
    EXPECT_EQ(scratch.fileCount(), 1u);  // no temporary files either
}

TEST(OptimizationRun, NamesAnOutputDirectoryThatCannotBeCreated) {
    ScratchDirectory scratch;
    writeBytes(scratch / "taken", "a file");
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.3}}});
    try {
        runOptimization(loss, scene, fogJob(scratch / "taken", 1));
        FAIL() << "no error";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("taken"), std::string::npos) << error.what();
    }
}

TEST(LossChart, PlacesLossesOnALogScaleAndSkipsThoseItCannot) {
    std::vector<double> losses = {1.0, 0.1, 0.0, 0.01};
    std::string svg = lossChartSvg(losses, "l2");
    EXPECT_NE(svg.find(">1e-2<"), std::string::npos);
    EXPECT_NE(svg.find(">1e0<"), std::string::npos);
    EXPECT_NE(svg.find("l2 loss"), std::string::npos);
    EXPECT_NE(svg.find(">iteration<"), std::string::npos);
    size_t points = svg.find("points=\"");
    std::string list = svg.substr(points, svg.find('"', points + 8) - points);
    EXPECT_EQ(std::count(list.begin(), list.end(), ','), 3);
}

}  // namespace
}  // namespace vkdr::test
