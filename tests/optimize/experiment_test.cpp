// Experiment files: reading, validation against the scene, and a whole run with an
// analytic stand-in for the renderer.
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../image/scratch_directory.h"
#include "core/error.h"
#include "expect_error.h"
#include "optimize/experiment.h"
#include "optimize/experiment_run.h"
#include "optimize/iteration_log.h"
#include "quadratic_loss_gradient.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"
#include "volume/smoke_plume.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

using json = nlohmann::ordered_json;  // keeps "start" in the order written

const std::filesystem::path kScenes = VKDR_TEST_SCENES_DIR;

// An experiment on the shipped fog Cornell box, written into `directory`.
json fogExperiment(const std::filesystem::path& directory) {
    return {{"scene", std::filesystem::relative(kScenes / "cornell_fog.gltf", directory).string()},
            {"width", 8},
            {"height", 8},
            {"spp", 2},
            {"iterations", 300},
            {"learning_rate", 0.01},
            {"true", {{"media/fog/sigma_s", 0.0}, {"media/fog/sigma_a", 0.05}}},
            {"start", {{"media/fog/sigma_a", 0.3}, {"media/fog/g", {0.5}}}}};
}

std::filesystem::path writeExperiment(const ScratchDirectory& scratch, const json& experiment) {
    std::filesystem::path file = scratch / "experiment.json";
    writeBytes(file, experiment.dump());
    return file;
}

void expectReadError(const ScratchDirectory& scratch, const json& experiment, const std::vector<std::string>& parts) {
    expectErrorMentioning([&] { readExperiment(writeExperiment(scratch, experiment)); }, parts);
}

void expectPrepareError(const ScratchDirectory& scratch, const json& experiment, const std::vector<std::string>& parts) {
    expectErrorMentioning(
        [&] {
            Experiment read = readExperiment(writeExperiment(scratch, experiment));
            Scene scene = loadScene(read.scene).scene;
            prepareExperimentScene(read, scene);
        },
        parts);
}

TEST(Experiment, ReadsEverySettingWithDefaultsForTheRest) {
    ScratchDirectory scratch;
    Experiment experiment = readExperiment(writeExperiment(scratch, fogExperiment(scratch.path())));
    EXPECT_TRUE(std::filesystem::equivalent(experiment.scene, kScenes / "cornell_fog.gltf"));
    EXPECT_EQ(experiment.views, std::vector<std::string>{""});  // the first camera
    EXPECT_EQ(experiment.render.width, 8);
    EXPECT_EQ(experiment.render.spp, 2u);
    EXPECT_EQ(experiment.targetSpp, 8u);
    EXPECT_EQ(experiment.loss, LossKind::L2);
    EXPECT_EQ(experiment.optimize.optimizer, OptimizerKind::Adam);
    EXPECT_EQ(experiment.optimize.iterations, 300u);
    // Without "parameters", the keys of "start" in file order.
    EXPECT_EQ(experiment.optimize.parameters, (std::vector<std::string>{"media/fog/sigma_a", "media/fog/g"}));
    ASSERT_EQ(experiment.trueValues.size(), 2u);
    EXPECT_EQ(experiment.trueValues[1].name, "media/fog/sigma_a");
    EXPECT_EQ(experiment.startValues[1].values, std::vector<float>{0.5f});
}

// A size written as a script's float prints (16.0) is a size; one side given alone
// leaves the other to the camera's aspect ratio, as render's --width and --height do.
TEST(Experiment, ReadsWholeNumbersWithAPointAndOneSideOfTheImage) {
    ScratchDirectory scratch;
    json experiment = fogExperiment(scratch.path());
    experiment["width"] = 16.0;
    experiment.erase("height");
    Experiment read = readExperiment(writeExperiment(scratch, experiment));
    EXPECT_EQ(read.render.width, 16);
    EXPECT_EQ(read.render.height, 0);
    experiment.erase("width");
    experiment["height"] = 8;
    read = readExperiment(writeExperiment(scratch, experiment));
    EXPECT_EQ(read.render.width, 0);
    EXPECT_EQ(read.render.height, 8);
    experiment.erase("height");
    read = readExperiment(writeExperiment(scratch, experiment));
    EXPECT_EQ(read.render.width, 128);
    EXPECT_EQ(read.render.height, 0);
}

TEST(Experiment, RejectsUnknownKeysWrongTypesAndAMissingScene) {
    ScratchDirectory scratch;
    json experiment = fogExperiment(scratch.path());
    experiment["iteratons"] = 5;
    expectReadError(scratch, experiment, {"experiment.json", "iteratons", "unknown key", "iterations"});

    experiment = fogExperiment(scratch.path());
    experiment["spp"] = "many";
    expectReadError(scratch, experiment, {"spp", "integer"});

    // Sizes and sample counts beyond the command line's bounds would overflow the renderer's counts.
    experiment = fogExperiment(scratch.path());
    experiment["target_spp"] = 4294967295u;
    expectReadError(scratch, experiment, {"target_spp", "[1, 1048576]"});
    experiment = fogExperiment(scratch.path());
    experiment["width"] = 3000000000u;
    expectReadError(scratch, experiment, {"width", "[1, 16384]"});

    experiment = fogExperiment(scratch.path());
    experiment["scene"] = "nowhere.gltf";
    expectReadError(scratch, experiment, {"scene", "nowhere.gltf", "no such file"});

    writeBytes(scratch / "target.exr", "not a scene");
    experiment["scene"] = "target.exr";
    expectReadError(scratch, experiment, {"experiment.json: scene: ", "target.exr: expected a .gltf or .glb file"});

    experiment["scene"] = "";
    expectReadError(scratch, experiment, {"scene", "empty: give a glTF path"});
    experiment.erase("scene");
    expectReadError(scratch, experiment, {"missing \"scene\""});

    // Named once, with the key.
    for (auto [key, value] : {std::pair{"optimizer", json("newton")}, std::pair{"optimizer", json(5)},
                              std::pair{"loss", json("l3")}, std::pair{"loss", json(2)}}) {
        experiment = fogExperiment(scratch.path());
        experiment[key] = value;
        try {
            readExperiment(writeExperiment(scratch, experiment));
            ADD_FAILURE() << key << " " << value << " was read";
        } catch (const Error& error) {
            const std::string message = error.what();
            EXPECT_NE(message.find("experiment.json: " + std::string(key) + ": "), std::string::npos) << message;
            EXPECT_EQ(message.find("experiment.json", message.find("experiment.json") + 1), std::string::npos)
                << message;
        }
    }
    experiment = fogExperiment(scratch.path());
    experiment["optimizer"] = "newton";
    expectReadError(scratch, experiment, {"experiment.json", "newton", "adam or sgd"});

    experiment = fogExperiment(scratch.path());
    experiment["start"]["media/fog/g"] = {0.1, 0.2};
    expectReadError(scratch, experiment, {"start.media/fog/g", "1 or 3 numbers"});

    writeBytes(scratch / "broken.json", "{\"scene\": ");
    expectErrorMentioning([&] { readExperiment(scratch / "broken.json"); },
                          {"broken.json: not valid JSON: parse error at line 1, column"});

    // A key given twice, at the top or inside an object, is refused rather than the last one kept.
    std::string text = fogExperiment(scratch.path()).dump();
    writeBytes(scratch / "twice.json", "{\"width\": 16, " + text.substr(1));
    expectErrorMentioning([&] { readExperiment(scratch / "twice.json"); },
                          {"twice.json", "width: given twice in one object"});
    const size_t start = text.find("\"start\":{") + std::string("\"start\":{").size();
    writeBytes(scratch / "twice.json", text.substr(0, start) + "\"media/fog/g\":0.1," + text.substr(start));
    expectErrorMentioning([&] { readExperiment(scratch / "twice.json"); }, {"start.media/fog/g: given twice"});
}

// Every integer is checked against its range as the number it is (beyond 32 bits, beyond
// int64, beyond 64 bits), and the message gives the range; rates must be finite and > 0.
TEST(Experiment, RejectsNumbersOutOfRangeNamingTheKeyAndTheRange) {
    ScratchDirectory scratch;
    auto expectRefused = [&](const std::string& key, json value, const std::vector<std::string>& parts) {
        json experiment = fogExperiment(scratch.path());
        experiment[key] = std::move(value);
        std::vector<std::string> all = {"experiment.json", key};
        all.insert(all.end(), parts.begin(), parts.end());
        expectReadError(scratch, experiment, all);
    };
    expectRefused("seed", 4294967296u, {"[0, 4294967295]", "4294967296"});
    expectRefused("seed", -3, {"[0, 4294967295]"});
    expectRefused("iterations", 18446744073709551615u, {"[1, 1000000]"});
    expectRefused("spp", json::parse("100000000000000000000000000000"), {"[1, 1048576]"});
    expectRefused("learning_rate", 0.0, {"finite number > 0"});
    // The command line's ranges (--lr-decay, --lr-decay-start).
    expectRefused("learning_rate_decay", 1e-12, {"[1e-09, 1]"});
    expectRefused("learning_rate_decay", 2.0, {"[1e-09, 1]"});
    expectRefused("learning_rate_decay_start", 0.9999, {"[0, 0.999]"});
    expectRefused("adam_epsilon", -1e-8, {"finite number > 0", "got -1e-08"});
    expectRefused("iterations", "3", {"[1, 1000000]", "got \"3\""});
    expectRefused("height", nullptr, {"[1, 16384]", "got null"});
    expectRefused("width", 16.5, {"[1, 16384]", "got 16.5"});
    // The command line's range (--smoothness and the other priors' weights).
    for (const char* prior : {"smoothness", "sparsity", "total_variation"}) {
        expectRefused(prior, 1e13, {"[0, 1e+12]", "got 10000000000000.0"});
        expectRefused(prior, -1.0, {"[0, 1e+12]", "got -1.0"});
    }
    expectRefused("learning_rates", {{"media/fog/sigma_a", -2.0}}, {"learning_rates.media/fog/sigma_a", "> 0"});
    expectRefused("start", {{"media/fog/sigma_a", 1e39}}, {"start.media/fog/sigma_a", "float range"});
    // The field of view as the camera keeps it, in float radians: 1e-300 is 0 there, and
    // 179.99999999 is 180.
    for (double yfov : {1e300, 1e-300, 179.99999999}) {
        expectRefused("cameras",
                      {{{"name", "c"}, {"position", {0, 0, 0}}, {"look_at", {0, 0, -1}}, {"yfov_degrees", yfov}}},
                      {"cameras[0].yfov_degrees", "above 0 and below 180 once rounded to a float"});
    }
    // A camera's vectors are three numbers, whatever else is given.
    for (json position : {json(5), json({5}), json({0, 1}), json("origin")}) {
        expectRefused("cameras", {{{"name", "c"}, {"position", position}, {"look_at", {0, 0, -1}}}},
                      {"cameras[0].position: expected an array of 3 numbers, got " + position.dump()});
    }
    // Each finite, but the view direction between them is not.
    expectRefused("cameras", {{{"name", "c"}, {"position", {3e38, 1, 5}}, {"look_at", {-3e38, 1, 0}}}},
                  {"cameras[0]", "the view they give is not finite"});
}

// Only a regular file is read: a directory is refused, and a FIFO without waiting for a writer.
TEST(Experiment, RefusesAFileOrSceneThatIsNotARegularFile) {
    ScratchDirectory scratch;
    expectNonRegularFilesRefused(scratch.path(), [](const std::filesystem::path& file) { readExperiment(file); });
    json experiment = fogExperiment(scratch.path());
    std::filesystem::create_directory(scratch / "folder.gltf");
    experiment["scene"] = "folder.gltf";
    expectReadError(scratch, experiment, {"experiment.json", "scene", "folder.gltf", "is a directory"});
}

TEST(Experiment, RejectsUnknownParametersValuesAndViewsAgainstTheScene) {
    ScratchDirectory scratch;
    json experiment = fogExperiment(scratch.path());
    experiment["parameters"] = {"media/smoke/g"};
    expectPrepareError(scratch, experiment, {"parameters", "unknown parameter 'media/smoke/g'", "media/fog/g"});

    experiment = fogExperiment(scratch.path());
    experiment["true"]["media/fog/g"] = 1.5;
    expectPrepareError(scratch, experiment, {"true.media/fog/g", "must be in [-0.99, 0.99], got 1.5"});

    experiment = fogExperiment(scratch.path());
    experiment["views"] = {"side"};
    expectPrepareError(scratch, experiment, {"views", "no camera 'side'", "camera"});

    experiment = fogExperiment(scratch.path());
    experiment["learning_rates"] = {{"media/fog/sigma_s", 0.1}};
    expectPrepareError(scratch, experiment, {"learning_rates.media/fog/sigma_s", "not one of the parameters"});

    experiment = fogExperiment(scratch.path());
    experiment["log_parameters"] = {"media/fog/sigma_s"};
    expectPrepareError(scratch, experiment, {"log_parameters", "media/fog/sigma_s", "not being optimised"});

    experiment = fogExperiment(scratch.path());
    experiment["log_parameters"] = {"media/fog/g"};
    expectPrepareError(scratch, experiment, {"log_parameters", "media/fog/g", "can be negative"});

    experiment = fogExperiment(scratch.path());
    experiment["start"]["media/fog/sigma_a"] = {0.3, 0.0, 0.3};
    experiment["log_parameters"] = {"media/fog/sigma_a"};
    expectPrepareError(scratch, experiment,
                       {"log_parameters", "media/fog/sigma_a", "value 1 of 3 (counted from 0): starts at 0",
                        "every value positive"});
}

TEST(Experiment, RefusesHeldOutViewsItCannotHoldOutAndGridSettingsWithoutAGrid) {
    ScratchDirectory scratch;
    json experiment = fogExperiment(scratch.path());
    experiment["held_out_views"] = {"side"};
    expectPrepareError(scratch, experiment, {"held_out_views", "no camera 'side'"});

    experiment["views"] = {"camera"};
    experiment["held_out_views"] = {"camera"};
    expectPrepareError(scratch, experiment, {"held_out_views", "'camera' is also a fitted view"});
    // The default view is the first camera, and so is "".
    experiment.erase("views");
    expectPrepareError(scratch, experiment, {"held_out_views", "'camera' is also a fitted view"});
    experiment["views"] = {""};
    expectPrepareError(scratch, experiment, {"held_out_views", "'camera' is also a fitted view"});
    // "" is the first camera only among the fitted views.
    experiment["held_out_views"] = {""};
    expectPrepareError(scratch, experiment, {"held_out_views", "\"\" names no camera here", "cameras: camera"});

    // A camera fitted twice would only weigh double; listed twice, it is a slip.
    experiment.erase("held_out_views");
    experiment["views"] = {"", "camera"};
    expectPrepareError(scratch, experiment, {"views", "camera 'camera' is listed twice", "the first camera"});
    experiment["views"] = json::array();
    expectReadError(scratch, experiment, {"views", "empty", "leave \"views\" out for the first camera"});

    experiment = fogExperiment(scratch.path());
    experiment["smoothness"] = -1.0;
    expectReadError(scratch, experiment, {"smoothness", "expected a number in [0, 1e+12], got -1.0"});
    experiment["smoothness"] = 0.5;
    expectPrepareError(scratch, experiment, {"smoothness", "no grid (media/<medium>/density or"});

    experiment = fogExperiment(scratch.path());
    experiment["sparsity"] = "a lot";
    expectReadError(scratch, experiment, {"sparsity", "expected a number in [0, 1e+12], got \"a lot\""});
    experiment["sparsity"] = 2.0;
    expectPrepareError(scratch, experiment, {"sparsity", "no grid (media/<medium>/density or"});

    experiment = fogExperiment(scratch.path());
    experiment["total_variation"] = -0.5;
    expectReadError(scratch, experiment, {"total_variation", "expected a number in [0, 1e+12], got -0.5"});
    experiment["total_variation"] = 0.5;
    expectPrepareError(scratch, experiment, {"total_variation", "no grid (media/<medium>/density or"});

    experiment = fogExperiment(scratch.path());
    experiment["grid_levels"] = 3;
    expectPrepareError(scratch, experiment, {"grid_levels", "no grid (media/<medium>/density or"});
    experiment["grid_levels"] = 11;
    expectReadError(scratch, experiment, {"grid_levels", "[1, 10]"});
}

TEST(Experiment, AddsItsCamerasToTheScene) {
    ScratchDirectory scratch;
    json experiment = fogExperiment(scratch.path());
    experiment["views"] = {"camera", "side"};
    experiment["cameras"] = {{{"name", "side"}, {"position", {0, 2, -4}}, {"look_at", {0, 2, 0}}, {"yfov_degrees", 30}}};
    Experiment read = readExperiment(writeExperiment(scratch, experiment));
    Scene scene = loadScene(read.scene).scene;
    prepareExperimentScene(read, scene);
    ASSERT_EQ(scene.cameras.size(), 2u);
    const Camera& side = scene.cameras[1];
    EXPECT_EQ(side.name, "side");
    // Looks down its -Z axis, from its position, towards look_at (+Z in the world).
    glm::vec4 position = side.cameraToWorld * glm::vec4(0, 0, 0, 1);
    glm::vec4 forward = side.cameraToWorld * glm::vec4(0, 0, -1, 0);
    EXPECT_NEAR(position.y, 2.0f, 1e-6f);
    EXPECT_NEAR(position.z, -4.0f, 1e-6f);
    EXPECT_NEAR(forward.z, 1.0f, 1e-6f);
    EXPECT_NEAR(side.yfov, glm::radians(30.0f), 1e-6f);

    // An orthographic one: parallel rays through a view of that half height.
    experiment["cameras"][0].erase("yfov_degrees");
    experiment["cameras"][0]["orthographic_half_height"] = 1.5;
    read = readExperiment(writeExperiment(scratch, experiment));
    scene = loadScene(read.scene).scene;
    prepareExperimentScene(read, scene);
    EXPECT_TRUE(scene.cameras[1].orthographic());
    EXPECT_EQ(scene.cameras[1].orthographicHalfHeight, 1.5f);
    EXPECT_FALSE(scene.cameras[0].orthographic());
    experiment["cameras"][0]["orthographic_half_height"] = 0.0;
    expectReadError(scratch, experiment, {"cameras[0].orthographic_half_height", "finite number > 0"});
    experiment["cameras"][0]["orthographic_half_height"] = 1e39;
    expectReadError(scratch, experiment, {"cameras[0].orthographic_half_height", "a normal float"});
    experiment["cameras"][0]["orthographic_half_height"] = 1e-50;  // 0 as a float: no orthographic camera
    expectReadError(scratch, experiment, {"cameras[0].orthographic_half_height", "a normal float"});
    experiment["cameras"][0]["orthographic_half_height"] = 1e-39;  // subnormal: a device may flush it to 0
    expectReadError(scratch, experiment, {"cameras[0].orthographic_half_height", "a normal float"});
    experiment["cameras"][0]["orthographic_half_height"] = 1.5;
    experiment["cameras"][0]["yfov_degrees"] = 30;
    expectReadError(scratch, experiment, {"cameras[0]", "not both"});
    experiment["cameras"][0].erase("yfov_degrees");

    experiment["cameras"][0]["look_at"] = {0, 2, -4};
    expectReadError(scratch, experiment, {"cameras[0]", "look_at must differ"});
    experiment["cameras"][0]["name"] = "";
    expectReadError(scratch, experiment, {"cameras[0].name", "must not be empty"});
    // A name labels printed figures, one line each: a newline or a NUL would break or cut them.
    experiment["cameras"][0]["name"] = "line\nbreak";
    expectReadError(scratch, experiment, {"cameras[0].name", "must not hold control characters", "line\\x0abreak"});
    experiment["cameras"][0]["name"] = std::string("cut\0short", 9);
    expectReadError(scratch, experiment, {"cameras[0].name", "must not hold control characters", "cut\\x00short"});
}

TEST(Experiment, RecoversTheTrueValuesWithAnAnalyticBackend) {
    ScratchDirectory scratch;
    Experiment experiment = readExperiment(writeExperiment(scratch, fogExperiment(scratch.path())));
    Scene scene = loadScene(experiment.scene).scene;

    std::vector<RenderSettings> targetRenders;
    ExperimentBackend backend;
    // A "render" that shows sigma_a; the loss gradient's minimum is the value the
    // target was rendered with.
    backend.render = [&](const Scene& rendered, const RenderSettings& settings) {
        targetRenders.push_back(settings);
        float sigma_a = getParameter(rendered, "media/fog/sigma_a")[0];
        return Image{settings.width, settings.height, std::vector<float>(size_t(settings.width * settings.height * 3), sigma_a)};
    };
    backend.makeLossGradient = [&](const Scene& start, std::vector<TargetView> views, std::vector<std::string> names,
                                   const RenderSettings&, LossKind) -> std::unique_ptr<LossGradient> {
        EXPECT_EQ(getParameter(start, "media/fog/sigma_a")[0], 0.3f);
        EXPECT_EQ(names, experiment.optimize.parameters);
        const Image& target = views.at(0).target;
        double truth = target.rgb[0];
        auto loss = std::make_unique<QuadraticLossGradient>(
            QuadraticLossGradient::Minima{{"media/fog/sigma_a", {truth, truth, truth}}, {"media/fog/g", {0.0}}});
        loss->setImageSize(target.width, target.height);
        return loss;
    };
    OptimizationReport report =
        runExperiment(experiment, scene, backend, startExperiment(experiment, scene, scratch / "out"));

    ASSERT_EQ(targetRenders.size(), 1u);
    EXPECT_EQ(targetRenders[0].spp, 8u);
    EXPECT_EQ(targetRenders[0].seed, kTargetSeedOffset);
    ASSERT_EQ(report.parameters.size(), 2u);
    EXPECT_EQ(report.parameters[0].truth, std::vector<float>(3, 0.05f));
    EXPECT_EQ(report.parameters[0].start, std::vector<float>(3, 0.3f));
    EXPECT_NEAR(report.parameters[0].fitted[0], 0.05f, 1e-3f);
    EXPECT_EQ(getParameter(scene, "media/fog/sigma_s"), std::vector<float>(3, 0.0f));  // "true" values stay

    std::string table = parameterTable(report.parameters);
    EXPECT_NE(table.find("media/fog/sigma_a"), std::string::npos);
    EXPECT_NE(table.find("%"), std::string::npos);
    EXPECT_NE(table.find("abs"), std::string::npos);  // g's true value is 0
    for (const char* file : {"log.jsonl", "params.json", "scene.gltf", "target.exr", "diff.png", "report.html"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(scratch / "out" / file)) << file;
    }
}

// scene.gltf goes last: a scene file edited during the run is refused there, and every
// other output, the rendered target among them, is written all the same.
TEST(Experiment, WritesItsTargetWhenTheFittedSceneIsRefused) {
    ScratchDirectory scratch;
    std::filesystem::copy_file(kScenes / "cornell_fog.gltf", scratch / "fog.gltf");
    json description = fogExperiment(scratch.path());
    description["scene"] = "fog.gltf";
    description["iterations"] = 3;
    description["learning_rates"] = {{"media/fog/g", 0.05}};
    Experiment experiment = readExperiment(writeExperiment(scratch, description));
    Scene scene = loadScene(experiment.scene).scene;
    ExperimentBackend backend;
    backend.render = [](const Scene&, const RenderSettings& settings) {
        return Image{settings.width, settings.height, std::vector<float>(size_t(settings.width * settings.height * 3), 0.5f)};
    };
    backend.makeLossGradient = [&](const Scene&, std::vector<TargetView> views, std::vector<std::string>,
                                   const RenderSettings&, LossKind) -> std::unique_ptr<LossGradient> {
        std::ofstream(scratch / "fog.gltf", std::ios::app) << " ";  // edited once the run has started
        auto loss = std::make_unique<QuadraticLossGradient>(
            QuadraticLossGradient::Minima{{"media/fog/sigma_a", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.0}}});
        loss->setImageSize(views.at(0).target.width, views.at(0).target.height);
        return loss;
    };
    expectErrorMentioning(
        [&] { runExperiment(experiment, scene, backend, startExperiment(experiment, scene, scratch / "out")); },
        {"fog.gltf", "scene.gltf is not written, and the run's other outputs are in", "params.json holds"});
    for (const char* file : {"params.json", "report.html", "target.exr", "target.png"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(scratch / "out" / file)) << file;
    }
    EXPECT_FALSE(std::filesystem::exists(scratch / "out" / "scene.gltf"));
    const std::string report = readBytes(scratch / "out" / "report.html");
    EXPECT_NE(report.find("<th>learning rate of media/fog/g</th><td>0.05</td>"), std::string::npos);
}

// A run directory that cannot be resumed, or that holds another run, is refused by
// startExperiment, which renders nothing (runExperiment renders the targets).
TEST(Experiment, StartRefusesARunDirectoryItCannotUse) {
    ScratchDirectory scratch;
    Experiment experiment = readExperiment(writeExperiment(scratch, fogExperiment(scratch.path())));
    std::filesystem::create_directory(scratch / "out");
    Scene scene = loadScene(experiment.scene).scene;
    expectErrorMentioning([&] { startExperiment(experiment, scene, scratch / "out", true); }, {"checkpoint.json"});
    std::ofstream(scratch / "out" / "log.jsonl") << "{}\n";
    scene = loadScene(experiment.scene).scene;  // startExperiment has added the experiment's cameras to it
    expectErrorMentioning([&] { startExperiment(experiment, scene, scratch / "out"); }, {"log.jsonl"});
}

// A held-out view renders its target once and, at every iteration, with the same
// samples as the true scene's render of it: its error falls to that floor as the fit
// converges, and is logged with the iteration.
TEST(Experiment, MeasuresTheHeldOutViewAtEveryIteration) {
    ScratchDirectory scratch;
    json file = fogExperiment(scratch.path());
    file["iterations"] = 200;
    file["cameras"] = {{{"name", "side"}, {"position", {0, 2, -4}}, {"look_at", {0, 2, 0}}}};
    file["views"] = {"camera"};
    file["held_out_views"] = {"side"};
    Experiment experiment = readExperiment(writeExperiment(scratch, file));
    Scene scene = loadScene(experiment.scene).scene;
    std::vector<RenderSettings> renders;
    ExperimentBackend backend;
    backend.render = [&](const Scene& rendered, const RenderSettings& settings) {
        renders.push_back(settings);
        float sigma_a = getParameter(rendered, "media/fog/sigma_a")[0];
        return Image{settings.width, settings.height, std::vector<float>(size_t(settings.width * settings.height * 3), 1.0f + sigma_a)};
    };
    backend.makeLossGradient = [&](const Scene&, std::vector<TargetView> views, std::vector<std::string>,
                                   const RenderSettings&, LossKind) -> std::unique_ptr<LossGradient> {
        const Image& target = views.at(0).target;
        double truth = target.rgb[0] - 1.0;
        auto loss = std::make_unique<QuadraticLossGradient>(
            QuadraticLossGradient::Minima{{"media/fog/sigma_a", {truth, truth, truth}}, {"media/fog/g", {0.0}}});
        loss->setImageSize(target.width, target.height);
        return loss;
    };
    OptimizationReport report =
        runExperiment(experiment, scene, backend, startExperiment(experiment, scene, scratch / "out"));

    // The fitted view's target, the held-out target, the true held-out render, then one
    // render of the held-out view per iteration with the same seed.
    ASSERT_EQ(renders.size(), 3u + 200u);
    EXPECT_EQ(renders[1].camera, "side");
    EXPECT_EQ(renders[1].seed, kTargetSeedOffset);
    EXPECT_EQ(renders[2].seed, kHeldOutSeedOffset);
    EXPECT_EQ(renders[2].spp, experiment.render.spp);
    EXPECT_EQ(renders.back().seed, kHeldOutSeedOffset);
    ASSERT_EQ(report.result.lastMetrics.size(), 2u);
    EXPECT_EQ(report.result.lastMetrics[0].name, "held-out side relative RMSE");
    EXPECT_NEAR(report.result.lastMetrics[0].value, 0.0, 1e-3);
    std::vector<MetricSeries> metrics = readMetrics(scratch / "out" / "log.jsonl");
    ASSERT_EQ(metrics.size(), 2u);
    EXPECT_NEAR(metrics[0].values[0], 0.25 / 1.05, 1e-6);  // the start 0.3 against the truth 0.05
}

// A held-out view whose target is black has no error relative to it: refused naming the
// experiment, its field and the camera, before any iteration.
TEST(Experiment, RefusesAHeldOutViewWhoseTargetIsBlack) {
    ScratchDirectory scratch;
    json file = fogExperiment(scratch.path());
    file["cameras"] = {{{"name", "side"}, {"position", {0, 2, -4}}, {"look_at", {0, 2, 0}}}};
    file["views"] = {"camera"};
    file["held_out_views"] = {"side"};
    Experiment experiment = readExperiment(writeExperiment(scratch, file));
    Scene scene = loadScene(experiment.scene).scene;
    ExperimentBackend backend;
    backend.render = [&](const Scene&, const RenderSettings& settings) {
        float value = settings.camera == "side" ? 0.0f : 1.0f;
        return Image{settings.width, settings.height, std::vector<float>(size_t(settings.width * settings.height * 3), value)};
    };
    backend.makeLossGradient = [&](const Scene&, std::vector<TargetView>, std::vector<std::string>,
                                   const RenderSettings&, LossKind) -> std::unique_ptr<LossGradient> {
        ADD_FAILURE() << "no loss gradient is made for a refused run";
        return nullptr;
    };
    expectErrorMentioning(
        [&] { runExperiment(experiment, scene, backend, startExperiment(experiment, scene, scratch / "out")); },
                          {experiment.file.string(), "held_out_views", "camera 'side' is black"});
}

TEST(Experiment, ShippedExperimentsMatchTheirScenes) {
    std::filesystem::path directory = kScenes / "experiments";
    for (const char* name : {"cornell_absorption.json", "smoke_g_and_colour.json", "smoke_reconstruction.json"}) {
        SCOPED_TRACE(name);
        Experiment experiment = readExperiment(directory / name);
        Scene scene = loadScene(experiment.scene).scene;
        prepareExperimentScene(experiment, scene);
    }
}

// The 256^3 experiment's grid is made, not shipped: a small plume stands in for it.
TEST(Experiment, TheGridExperimentForAGpuMatchesItsScene) {
    ScratchDirectory scratch;
    for (const char* name : {"smoke_reconstruction_256.json", "smoke_plume_256.gltf"}) {
        std::filesystem::copy_file(kScenes / "experiments" / name, scratch / name);
    }
    writeDensityGridVdb(scratch / "smoke_plume_256.vdb", makeSmokePlume(8, 2));
    Experiment experiment = readExperiment(scratch / "smoke_reconstruction_256.json");
    EXPECT_EQ(experiment.views.size(), 32u);
    EXPECT_EQ(experiment.render.width, 256u);
    Scene scene = loadScene(experiment.scene).scene;
    prepareExperimentScene(experiment, scene);
}

}  // namespace
}  // namespace vkdr::test
