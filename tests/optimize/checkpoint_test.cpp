// Checkpoints and --resume: a run stopped at any point and resumed ends exactly where
// the uninterrupted run ends; a resume that does not match its checkpoint is refused.
#include <bit>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../image/scratch_directory.h"
#include "core/error.h"
#include "expect_error.h"
#include "optimize/adam.h"
#include "optimize/checkpoint.h"
#include "optimize/optimization_run.h"
#include "quadratic_loss_gradient.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

const std::filesystem::path kFogScene = std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_fog.gltf";

QuadraticLossGradient::Minima fogMinima() { return {{"media/fog/sigma_a", {0.05, 0.1, 0.2}}, {"media/fog/g", {0.3}}}; }

OptimizationJob fogJob(const std::filesystem::path& directory, uint32_t iterations) {
    OptimizationJob job;
    job.sceneFile = kFogScene;
    job.outputDirectory = directory;
    job.options.parameters = {"media/fog/sigma_a", "media/fog/g"};
    job.options.learningRate = 0.01;
    job.options.learningRateDecay = 0.5;
    job.options.iterations = iterations;
    job.options.seed = 7;
    job.options.checkpointEvery = 10;
    job.inputs.spp = 4;
    job.targets = {{"", Image{4, 3, std::vector<float>(4 * 3 * 3, 0.05f)}}};
    return job;
}

using EditJson = std::function<void(nlohmann::ordered_json&)>;

// Writes `document` with `edit` applied as the checkpoint `file`, and expects reading it
// to fail with an error naming the file and each of `parts`.
void expectEditRefused(const std::filesystem::path& file, const nlohmann::ordered_json& document,
                       const EditJson& edit, const std::vector<std::string>& parts) {
    nlohmann::ordered_json edited = document;
    edit(edited);
    writeBytes(file, edited.dump());
    std::vector<std::string> all = {file.string()};
    all.insert(all.end(), parts.begin(), parts.end());
    expectErrorMentioning([&] { readCheckpoint(file); }, all);
}

// Runs `job` until the evaluation `stopAt` fails, as a killed process would stop.
void runUntil(const OptimizationJob& job, size_t stopAt) {
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss(fogMinima());
    loss.failFrom(stopAt, "media/fog/g");
    EXPECT_THROW(runOptimization(loss, scene, job), Error);
}

// log.jsonl's lines without their "iteration_ms", which no two runs share.
std::vector<std::string> logWithoutWallClock(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
        nlohmann::ordered_json record = nlohmann::ordered_json::parse(line);
        EXPECT_TRUE(record.contains("iteration_ms")) << line;
        record.erase("iteration_ms");
        lines.push_back(record.dump());
    }
    return lines;
}

TEST(Checkpoint, AResumedRunEndsExactlyWhereTheUninterruptedRunEnds) {
    ScratchDirectory scratch;
    Scene whole = loadScene(kFogScene).scene;
    QuadraticLossGradient wholeLoss(fogMinima());
    runOptimization(wholeLoss, whole, fogJob(scratch / "whole", 40));

    // Stopped two iterations after the checkpoint at 20: those two are logged but lost.
    OptimizationJob job = fogJob(scratch / "resumed", 40);
    runUntil(job, 22);
    ASSERT_EQ(readCheckpoint(scratch / "resumed" / kCheckpointFileName).state.iteration, 20u);

    job.resume = true;
    Scene resumed = loadScene(kFogScene).scene;
    QuadraticLossGradient resumedLoss(fogMinima());
    OptimizationReport report = runOptimization(resumedLoss, resumed, job);
    // First, once at the start values with iteration 0's seed: the report's start images,
    // which the stopped process rendered and did not keep (before the loop, so that a
    // signal after its last iteration has no render to stop). Then the 20 iterations
    // left, iteration i still rendering with seed + i.
    ASSERT_EQ(resumedLoss.seeds().size(), 21u);
    EXPECT_EQ(resumedLoss.seeds().front(), 7u);
    EXPECT_EQ(resumedLoss.seeds()[1], 7u + 20u);
    EXPECT_EQ(resumedLoss.seeds().back(), 7u + 39u);
    EXPECT_EQ(report.result.losses.size(), 40u);

    for (const char* name : {"media/fog/sigma_a", "media/fog/g"}) {
        EXPECT_EQ(getParameter(resumed, name), getParameter(whole, name)) << name;
    }
    // Every line once, and bit for bit what the uninterrupted run logged, but for the
    // wall clock of each iteration.
    EXPECT_EQ(logWithoutWallClock(scratch / "resumed" / "log.jsonl"), logWithoutWallClock(scratch / "whole" / "log.jsonl"));
    for (const char* file : {"params.json", "loss.svg", "scene.gltf"}) {
        EXPECT_EQ(readBytes(scratch / "resumed" / file), readBytes(scratch / "whole" / file)) << file;
    }
}

TEST(Checkpoint, IsWrittenEveryKIterationsButNotAfterTheLast) {
    ScratchDirectory scratch;
    OptimizationJob job = fogJob(scratch.path(), 30);
    job.options.checkpointEvery = 7;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss(fogMinima());
    runOptimization(loss, scene, job);
    Checkpoint checkpoint = readCheckpoint(scratch / kCheckpointFileName);
    EXPECT_EQ(checkpoint.state.iteration, 28u);
    EXPECT_EQ(checkpoint.state.losses.size(), 28u);
    EXPECT_EQ(checkpoint.state.optimizer.steps, 28u);
    EXPECT_EQ(checkpoint.state.optimizer.mean.size(), 4u);  // three sigma_a values and g
    EXPECT_EQ(checkpoint.run.at("optimizer"), "adam");
    EXPECT_EQ(checkpoint.run.at("spp"), "4");

    ScratchDirectory never;
    job = fogJob(never.path(), 30);
    job.options.checkpointEvery = 0;
    runOptimization(loss, scene, job);
    EXPECT_FALSE(std::filesystem::exists(never / kCheckpointFileName));
}

TEST(Checkpoint, ANonFiniteGradientLeavesTheLastCheckpointIntact) {
    ScratchDirectory scratch;
    OptimizationJob job = fogJob(scratch.path(), 40);
    runUntil(job, 25);
    EXPECT_EQ(readCheckpoint(scratch / kCheckpointFileName).state.iteration, 20u);
    for (const char* file : {"scene.gltf", "params.json", "final.exr", "loss.svg"}) {
        EXPECT_FALSE(std::filesystem::exists(scratch / file)) << file;
    }
    EXPECT_EQ(scratch.fileCount(), 2u);  // log.jsonl and checkpoint.json, no temporary files
}

TEST(Checkpoint, ResumeRefusesADifferentRun) {
    ScratchDirectory scratch;
    runUntil(fogJob(scratch.path(), 40), 15);
    auto expectRefused = [&](OptimizationJob job, const std::string& what) {
        job.resume = true;
        Scene scene = loadScene(job.sceneFile).scene;
        QuadraticLossGradient loss(fogMinima());
        expectErrorMentioning([&] { runOptimization(loss, scene, job); }, {"checkpoint.json", what});
    };
    OptimizationJob job = fogJob(scratch.path(), 40);
    job.options.learningRate = 0.02;
    expectRefused(job, "learning_rate");
    job = fogJob(scratch.path(), 40);
    job.options.optimizer = OptimizerKind::Sgd;
    expectRefused(job, "optimizer 'adam', but this run has 'sgd'");
    job = fogJob(scratch.path(), 40);
    job.options.parameters = {"media/fog/sigma_a"};
    expectRefused(job, "parameters");
    job = fogJob(scratch.path(), 40);
    job.inputs.spp = 8;
    expectRefused(job, "spp");

    std::filesystem::path edited = scratch / "edited.gltf";
    std::filesystem::copy_file(kFogScene, edited);
    std::ofstream(edited, std::ios::app) << "\n";
    job = fogJob(scratch.path(), 40);
    job.sceneFile = edited;
    expectRefused(job, "scene");
    EXPECT_EQ(readCheckpoint(scratch / kCheckpointFileName).state.iteration, 10u);  // untouched
}

// A command line's run is identified by its targets and --set values, an experiment's by
// its file; both by the scene, the render settings and every option of the loop. The
// names are those checkpoints already on disk were written with.
TEST(RunIdentity, NamesTheInputsOfACommandLineOrOfAnExperiment) {
    ScratchDirectory scratch;
    const std::filesystem::path target = scratch.path() / "target.exr";
    std::ofstream(target) << "pixels";
    OptimizationJob job = fogJob(scratch.path(), 40);
    RunIdentity command = runIdentity(job.sceneFile, job.options, job.loss,
                                      {{}, {{"side", target}, {"", target}}, {"media/fog/g=0.2", "media/fog/sigma_s=1"}, 4, 6});
    EXPECT_EQ(command.at("targets"), "side=" + fileDigest(target) + "; " + fileDigest(target));
    EXPECT_EQ(command.at("set"), "media/fog/g=0.2 media/fog/sigma_s=1");
    // The values set, not how they were typed.
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss,
                          {{}, {{"side", target}}, {"media/fog/g=0.20", "media/fog/sigma_s=1e0,.5,1.000"}, 4, 6})
                  .at("set"),
              "media/fog/g=0.2 media/fog/sigma_s=1,0.5,1");
    // One value repeated sets what the value alone does; -0 and 0 are other bits.
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss,
                          {{}, {{"side", target}}, {"media/fog/sigma_s=0.5,.5,5e-1", "media/fog/sigma_a=-0,0,0"}, 4, 6})
                  .at("set"),
              "media/fog/sigma_a=-0,0,0 media/fog/sigma_s=0.5");
    // In the order of the names, whatever order they were given in; the last of a name,
    // which is the one --set applies.
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss,
                          {{}, {{"side", target}}, {"media/fog/sigma_s=1", "media/fog/g=0.2"}, 4, 6})
                  .at("set"),
              command.at("set"));
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss,
                          {{}, {{"side", target}}, {"media/fog/g=0.7", "media/fog/sigma_s=1", "media/fog/g=0.2"}, 4, 6})
                  .at("set"),
              command.at("set"));
    EXPECT_EQ(command.at("spp"), "4");
    EXPECT_EQ(command.at("max_depth"), "6");
    EXPECT_EQ(command.at("scene"), "cornell_fog.gltf, " + fileDigest(kFogScene));
    EXPECT_EQ(command.at("parameters"), "media/fog/sigma_a media/fog/g");
    EXPECT_EQ(command.at("learning_rate_decay"), "0.5");
    EXPECT_EQ(command.count("experiment"), 0u);

    RunIdentity experiment = runIdentity(job.sceneFile, job.options, job.loss, {target, {}, {}, 4, 6});
    EXPECT_EQ(experiment.at("experiment"), "target.exr, " + fileDigest(target));
    EXPECT_EQ(experiment.count("targets") + experiment.count("set"), 0u);
    for (const char* option : {"optimizer", "learning_rate", "learning_rates", "learning_rate_decay_start",
                               "log_parameters", "adam_epsilon", "smoothness", "sparsity", "grid_levels", "iterations", "seed",
                               "loss"}) {
        EXPECT_EQ(command.at(option), experiment.at(option)) << option;
    }
    EXPECT_EQ(command.size(), 19u);
    EXPECT_EQ(experiment.size(), 18u);
    // A total variation weight joins the identity only where set: runs without one keep theirs.
    EXPECT_EQ(command.count("total_variation"), 0u);
    job.options.totalVariation = 0.25;
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss, {target, {}, {}, 4, 6}).at("total_variation"), "0.25");
    // So does equiangular sampling where it is off (--no-equiangular): it changes every render.
    EXPECT_EQ(command.count("equiangular_sampling"), 0u);
    EXPECT_EQ(runIdentity(job.sceneFile, job.options, job.loss, {target, {}, {}, 4, 6, false}).at("equiangular_sampling"),
              "off");
}

// A checkpoint written before --set values were recorded as floats holds them as typed:
// it resumes with the same values typed any way, and not with others.
TEST(RunIdentity, ComparesAnOlderCheckpointsSetValuesAsFloats) {
    const RunIdentity current = {{"set", canonicalAssignment("materials/My Mat/base_color=0.5,1,1") + " " +
                                             canonicalAssignment("media/fog/g=0.2")}};
    EXPECT_EQ(current.at("set"), "materials/My Mat/base_color=0.5,1,1 media/fog/g=0.2");
    requireSameRun("checkpoint.json", {{"set", "materials/My Mat/base_color=.50,1.0,1e0 media/fog/g=0.20"}}, current);
    expectErrorMentioning([&] { requireSameRun("checkpoint.json", {{"set", "media/fog/g=0.3"}}, current); },
                          {"checkpoint.json", "set 'media/fog/g=0.3'"});
    // A name may hold "=" and a space; an older entry splits at the words where an
    // assignment ends, and the current run's is split alike.
    ScratchDirectory scratch;
    const std::filesystem::path target = scratch.path() / "target.exr";
    std::ofstream(target) << "pixels";
    OptimizationJob job = fogJob(scratch.path(), 40);
    const RunIdentity named = runIdentity(job.sceneFile, job.options, job.loss,
                                          {{}, {{"", target}}, {"materials/k=1.0 glass/base_color=0.50"}, 4, 6});
    RunIdentity older = named;
    older["set"] = "materials/k=1.0 glass/base_color=0.50";
    requireSameRun("checkpoint.json", older, named);
}

// Options are numbers in their shortest text (0.01, as typed). A checkpoint that holds
// them with 17 digits resumes with the same numbers, and a refusal prints them short.
TEST(RunIdentity, WritesOptionsAsTheShortestNumbersAndReadsOlderLongOnes) {
    ScratchDirectory scratch;
    const std::filesystem::path target = scratch.path() / "target.exr";
    std::ofstream(target) << "pixels";
    OptimizationJob job = fogJob(scratch.path(), 40);
    job.options.learningRate = 0.01;
    job.options.learningRates = {{"media/fog/g", 0.1}};
    const RunIdentity current = runIdentity(job.sceneFile, job.options, job.loss, {target, {}, {}, 4, 6});
    EXPECT_EQ(current.at("learning_rate"), "0.01");
    EXPECT_EQ(current.at("learning_rates"), "media/fog/g=0.1");
    RunIdentity older = current;
    older["learning_rate"] = "0.01000000000000000021";
    older["learning_rates"] = "media/fog/g=0.10000000000000001";
    requireSameRun("checkpoint.json", older, current);
    older["learning_rate"] = "0.02000000000000000042";
    expectErrorMentioning([&] { requireSameRun("checkpoint.json", older, current); },
                          {"learning_rate '0.02', but this run has '0.01'"});
}

TEST(Checkpoint, ResumeNamesAMissingOrDamagedCheckpoint) {
    ScratchDirectory scratch;
    OptimizationJob job = fogJob(scratch.path(), 40);
    job.resume = true;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss(fogMinima());
    expectErrorMentioning([&] { runOptimization(loss, scene, job); }, {"--resume", "no checkpoint.json"});

    writeBytes(scratch / kCheckpointFileName, "{\"format\": \"vkdiffrender optimize checkpoint 1\", \"run\": {");
    expectErrorMentioning([&] { runOptimization(loss, scene, job); },
                          {"checkpoint.json", "not valid JSON (damaged or cut short): parse error at line 1, column"});
    writeBytes(scratch / kCheckpointFileName, "\n");
    expectErrorMentioning([&] { readCheckpoint(scratch / kCheckpointFileName); }, {"checkpoint.json: empty"});
    writeBytes(scratch / kCheckpointFileName, "{\"format\": \"vkdiffrender optimize checkpoint 1\", \"run\": {}}");
    expectErrorMentioning([&] { readCheckpoint(scratch / kCheckpointFileName); }, {"checkpoint.json", "iteration"});
    writeBytes(scratch / kCheckpointFileName, "[1, 2]");
    expectErrorMentioning([&] { readCheckpoint(scratch / kCheckpointFileName); },
                          {"checkpoint.json", "expected a JSON object, got array"});
    // A key edited twice: neither value is taken over the other.
    writeBytes(scratch / kCheckpointFileName,
               "{\"format\": \"vkdiffrender optimize checkpoint 1\", \"run\": {\"seed\": 1, \"seed\": 2}}");
    expectErrorMentioning([&] { readCheckpoint(scratch / kCheckpointFileName); },
                          {"checkpoint.json", "seed: given twice in one object"});
}

// Only a regular file is read: a directory is refused, and a FIFO without waiting for a writer.
TEST(Checkpoint, RefusesWhatIsNotARegularFileNamingIt) {
    ScratchDirectory scratch;
    expectNonRegularFilesRefused(scratch.path(), [](const std::filesystem::path& file) { readCheckpoint(file); });
}

// A hand-edited checkpoint: values beyond float range and negative second moments would
// become infinities and NaNs in the run; they are refused naming the file and the key.
TEST(Checkpoint, RefusesNumbersOutOfRangeNamingTheFileAndKey) {
    ScratchDirectory scratch;
    OptimizationJob job = fogJob(scratch.path(), 6);
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss(fogMinima());
    job.options.checkpointEvery = 2;
    runOptimization(loss, scene, job);
    std::filesystem::path file = scratch / kCheckpointFileName;
    nlohmann::ordered_json good = nlohmann::ordered_json::parse(std::ifstream(file));
    auto expectRefused = [&](const EditJson& edit, const std::vector<std::string>& parts) {
        expectEditRefused(file, good, edit, parts);
    };
    expectRefused([](auto& d) { d["values"][0] = 1e300; }, {"values", "1e+300"});
    expectRefused([](auto& d) { d["optimizer"]["mean_square"][0] = -1.0; }, {"optimizer.mean_square", "[0, "});
    expectRefused([](auto& d) { d["iteration"] = 4294967296u; }, {"iteration", "[0, 4294967295]"});
    expectRefused([](auto& d) { d["optimizer"]["steps"] = -3; }, {"optimizer.steps", "integer"});
    expectRefused([](auto& d) { d["forward_ms"] = -1e300; }, {"forward_ms", "from 0 to 1e12"});
    expectRefused([](auto& d) { d["forward_ms"] = 1.7e308; }, {"forward_ms", "from 0 to 1e12"});
    expectRefused([](auto& d) { d["adjoint_ms"] = -1.0; }, {"adjoint_ms", "from 0 to 1e12"});
}

// A value within float range but outside its parameter's range (g = 5) is refused when
// the run resumes, naming the file and the parameter.
TEST(Checkpoint, ResumeRefusesAValueOutsideItsParametersRange) {
    ScratchDirectory scratch;
    OptimizationJob job = fogJob(scratch.path(), 6);
    job.options.checkpointEvery = 2;
    runUntil(job, 3);
    std::filesystem::path file = scratch / kCheckpointFileName;
    nlohmann::ordered_json document = nlohmann::ordered_json::parse(std::ifstream(file));
    document["values"][3] = 5.0;  // media/fog/g, after sigma_a's three
    writeBytes(file, document.dump());
    job.resume = true;
    Scene scene = loadScene(kFogScene).scene;
    QuadraticLossGradient loss(fogMinima());
    expectErrorMentioning([&] { runOptimization(loss, scene, job); },
                          {file.string(), "values", "media/fog/g[0]", "outside"});
    // Adam's step count, which its bias correction divides by, is one per iteration: a
    // count that wrapped round to 0 would make the first step NaN.
    document["values"][3] = 0.5;
    document["optimizer"]["steps"] = 18446744073709551615u;
    writeBytes(file, document.dump());
    expectErrorMentioning([&] { runOptimization(loss, scene, job); },
                          {file.string(), "optimizer.steps: expected 2, one per iteration done"});
}

// A density grid's checkpoint holds millions of numbers: vectors longer than 1024 are
// stored as base64 of their binary64 bits and read back bit for bit, every kind of double
// included; what a damaged or edited one holds is refused like an array's numbers.
TEST(Checkpoint, LongVectorsReadBackBitForBit) {
    ScratchDirectory scratch;
    Checkpoint checkpoint;
    checkpoint.run = {{"scene", "plume.gltf"}};
    LoopState& state = checkpoint.state;
    state.iteration = 3;
    for (int i = 0; i < 3000; ++i) {
        state.values.push_back(std::ldexp(1.0 + i / 3001.0, i % 200 - 100) * (i % 3 == 0 ? -1.0 : 1.0));
    }
    state.values[1] = -0.0;
    state.values[2] = 4.9e-324;  // the smallest subnormal
    state.optimizer = {3, state.values, std::vector<double>(3000, 1.0 / 3.0)};
    state.losses = {0.5, 0.25, 0.125};
    const std::filesystem::path file = scratch / kCheckpointFileName;
    writeCheckpoint(file, checkpoint);
    nlohmann::ordered_json document = nlohmann::ordered_json::parse(std::ifstream(file));
    EXPECT_TRUE(document["values"].is_string());
    EXPECT_TRUE(document["losses"].is_array());  // short vectors stay readable
    Checkpoint read = readCheckpoint(file);
    auto bits = [](const std::vector<double>& values) {
        std::vector<uint64_t> result;
        for (double value : values) result.push_back(std::bit_cast<uint64_t>(value));
        return result;
    };
    EXPECT_EQ(bits(read.state.values), bits(state.values));
    EXPECT_EQ(bits(read.state.optimizer.mean), bits(state.optimizer.mean));
    EXPECT_EQ(read.state.optimizer.meanSquare, state.optimizer.meanSquare);
    EXPECT_EQ(read.state.losses, state.losses);
    EXPECT_EQ(read.run, checkpoint.run);

    auto expectRefused = [&](const EditJson& edit, const std::vector<std::string>& parts) {
        expectEditRefused(file, document, edit, parts);
    };
    expectRefused([](auto& d) { d["values"] = d["values"].template get<std::string>().substr(4); },
                  {"values", "base64"});
    expectRefused([](auto& d) { d["values"] = "AAAA"; }, {"values", "base64"});  // 3 bytes: no whole double
    expectRefused([](auto& d) { d["values"] = "AAAAAAAA!AA="; }, {"values", "base64"});
    expectRefused([](auto& d) { d["values"] = "AAAAAAAA8H8="; }, {"values", "got inf"});  // +infinity
    expectRefused([](auto& d) { d["optimizer"]["mean_square"] = "AAAAAAAA8L8="; }, {"optimizer.mean_square", "got -1"});
}

// A checkpoint of the first format (every vector an array) still resumes.
TEST(Checkpoint, ReadsTheFormatWithArraysOnly) {
    ScratchDirectory scratch;
    const std::filesystem::path file = scratch / kCheckpointFileName;
    writeBytes(file, R"({"format": "vkdiffrender optimize checkpoint 1", "run": {"scene": "a.gltf"},
        "iteration": 2, "values": [0.5, 0.25], "optimizer": {"steps": 2, "mean": [0.1, 0.2],
        "mean_square": [0.01, 0.04]}, "losses": [1.0, 0.5], "forward_ms": 3.0, "adjoint_ms": 4.0})");
    Checkpoint read = readCheckpoint(file);
    EXPECT_EQ(read.state.iteration, 2u);
    EXPECT_EQ(read.state.values, (std::vector<double>{0.5, 0.25}));
    EXPECT_EQ(read.state.optimizer.meanSquare, (std::vector<double>{0.01, 0.04}));
    EXPECT_EQ(read.state.adjointMs, 4.0);
}

TEST(Checkpoint, AdamContinuesFromItsStateExactly) {
    AdamOptimizer first(std::vector<double>(2, 0.1)), second(std::vector<double>(2, 0.1));
    std::vector<double> x = {1.0, -1.0}, y = x;
    std::vector<double> gradient = {0.3, -2.0};
    first.step(x, gradient);
    second.restore(first.state());
    y = x;
    first.step(x, gradient);
    second.step(y, gradient);
    EXPECT_EQ(x, y);
    EXPECT_THROW(second.restore(OptimizerState{1, {0.0}, {0.0}}), Error);
}

}  // namespace
}  // namespace vkdr::test
