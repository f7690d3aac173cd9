// optimize as a user meets a crash: the device is lost mid-run (simulated, see
// vk/simulated_device_loss.h), the run stops with one message and leaves its last
// checkpoint, and --resume finishes with the values of a run that never stopped.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.h"
#include "report_html_reader.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

// Setting up takes about twenty queue submissions and each iteration of this small
// problem about twenty more, so the device is lost in iteration 5 of 8: after the
// checkpoint at 4, with iteration 4 logged past it.
constexpr const char* kLoseDeviceMidRun = "VKDR_SIMULATE_DEVICE_LOST=130";

// Gradients are fixed-point sums, the same bits in whatever order the device's threads
// add them (docs/gradients.md), so a resumed run ends on exactly the values of one that
// was never stopped, with any number of lavapipe threads.
void expectSameValues(const nlohmann::json& resumed, const nlohmann::json& uninterrupted) {
    ASSERT_EQ(resumed.size(), uninterrupted.size());
    for (const auto& [name, values] : uninterrupted.items()) {
        ASSERT_TRUE(resumed.contains(name)) << name;
        ASSERT_EQ(resumed[name].size(), values.size()) << name;
        for (size_t i = 0; i < values.size(); ++i) {
            EXPECT_EQ(resumed[name][i].get<double>(), values[i].get<double>()) << name << "[" << i << "]";
        }
    }
}

class OptimizeResume : public ::testing::Test {
protected:
    void SetUp() override {
        scratch_ = fs::temp_directory_path() / ("vkdr-optimize-resume-" + std::to_string(getpid()));
        fs::remove_all(scratch_);
        fs::create_directories(scratch_);
        std::string fog = std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf";
        RunResult target = runCli("render " + fog + " --width 8 --height 8 --spp 4 --max-depth 2 -o " +
                                      (scratch_ / "target.exr").string(),
                                  scratch_);
        ASSERT_EQ(target.exitCode, 0) << target.err;
        command_ = "optimize " + fog + " --target " + (scratch_ / "target.exr").string() +
                   " --param media/fog/sigma_a --iters 8 --spp 1 --max-depth 2 --checkpoint-every 2";
    }
    void TearDown() override { fs::remove_all(scratch_); }

    fs::path scratch_;
    std::string command_;
};

TEST_F(OptimizeResume, ADeviceLostMidRunLeavesTheCheckpointAndResumeFinishesTheRun) {
    fs::path whole = scratch_ / "whole", cut = scratch_ / "cut";
    RunResult uninterrupted = runCli(command_ + " --out " + whole.string(), scratch_);
    ASSERT_EQ(uninterrupted.exitCode, 0) << uninterrupted.err;

    RunResult lost = runCli(command_ + " --out " + cut.string(), scratch_, kLoseDeviceMidRun);
    EXPECT_EQ(lost.exitCode, 2) << lost.err;
    EXPECT_EQ(lost.err.find("error: "), lost.err.rfind("error: ")) << lost.err;
    EXPECT_NE(lost.err.find("VK_ERROR_DEVICE_LOST"), std::string::npos) << lost.err;
    EXPECT_NE(lost.err.find("checkpoint.json is intact: run the same command with --resume"), std::string::npos)
        << lost.err;
    for (const char* file : {"params.json", "scene.gltf", "final.exr"}) {
        EXPECT_FALSE(fs::exists(cut / file)) << file;
    }
    nlohmann::json checkpoint = nlohmann::json::parse(slurp(cut / "checkpoint.json"));
    EXPECT_GE(checkpoint["iteration"].get<int>(), 2);

    RunResult resumed = runCli(command_ + " --resume " + cut.string(), scratch_);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    expectSameValues(nlohmann::json::parse(slurp(cut / "params.json")),
                     nlohmann::json::parse(slurp(whole / "params.json")));
    // The report covers the whole run: the start images, which the resumed process renders
    // again with iteration 0's seed, and the last ones are those of the run never stopped.
    std::string resumedReport = slurp(cut / "report.html"), wholeReport = slurp(whole / "report.html");
    for (const char* image : {"<img class=\"start\"", "<img class=\"current\"", "<img class=\"difference\""}) {
        std::vector<std::string> resumedImage = between(resumedReport, image, ">");
        ASSERT_EQ(resumedImage.size(), 1u) << image;
        EXPECT_EQ(resumedImage, between(wholeReport, image, ">")) << image;
    }
    EXPECT_EQ(between(resumedReport, "<polyline", "/>"), between(wholeReport, "<polyline", "/>"));
    std::istringstream log(slurp(cut / "log.jsonl"));
    int expected = 0;
    for (std::string line; std::getline(log, line); ++expected) {
        EXPECT_EQ(nlohmann::json::parse(line)["iteration"], expected);
    }
    EXPECT_EQ(expected, 8);
}

// The files of a run, as they stand.
std::map<std::string, std::string> runFiles(const fs::path& run) {
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(run)) {
        files[entry.path().filename().string()] = slurp(entry.path());
    }
    return files;
}

const std::vector<std::string> kOutputs = {"params.json", "scene.gltf", "final.exr", "final.png",
                                           "diff.png",    "loss.svg",   "report.html"};

// --resume from a finished run does its last iterations again. Stopped before it writes
// anything, it leaves the finished run as it was; stopped once it has rewritten the log
// back to the checkpoint, it must not leave the finished run's outputs beside that log,
// as if they were its own. Either way --resume then finishes the run.
TEST_F(OptimizeResume, AResumedFinishedRunStoppedShortLeavesTheRunBeforeWholeOrNoneOfItsOutputs) {
    fs::path run = scratch_ / "run";
    ASSERT_EQ(runCli(command_ + " --out " + run.string(), scratch_).exitCode, 0);
    const std::map<std::string, std::string> finished = runFiles(run);
    // Lost in the start renders a resumed run makes for its report, before its first iteration.
    RunResult early = runCli(command_ + " --resume " + run.string(), scratch_, "VKDR_SIMULATE_DEVICE_LOST=40");
    ASSERT_EQ(early.exitCode, 2) << early.err;
    EXPECT_EQ(runFiles(run), finished);
    // Lost in the last iteration, after the one before it was logged.
    RunResult late = runCli(command_ + " --resume " + run.string(), scratch_, "VKDR_SIMULATE_DEVICE_LOST=90");
    ASSERT_EQ(late.exitCode, 2) << late.err;
    const std::string log = slurp(run / "log.jsonl");
    EXPECT_LT(std::count(log.begin(), log.end(), '\n'), 8) << "the log goes back to the checkpoint";
    for (const std::string& file : kOutputs) EXPECT_FALSE(fs::exists(run / file)) << file;
    ASSERT_TRUE(fs::exists(run / "checkpoint.json"));
    RunResult resumed = runCli(command_ + " --resume " + run.string(), scratch_);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    expectSameValues(nlohmann::json::parse(slurp(run / "params.json")),
                     nlohmann::json::parse(finished.at("params.json")));
}

// A checkpoint edited to values the run cannot go on from (0, where the run steps in log
// space) is refused naming the file, and the finished run it belongs to stays whole.
TEST_F(OptimizeResume, ACheckpointThatLogSpaceCannotStartFromIsRefusedAndTheRunStaysWhole) {
    const std::string command = command_ + " --log-param media/fog/sigma_a";
    fs::path run = scratch_ / "run";
    ASSERT_EQ(runCli(command + " --out " + run.string(), scratch_).exitCode, 0);
    nlohmann::json checkpoint = nlohmann::json::parse(slurp(run / "checkpoint.json"));
    checkpoint["values"][1] = 0.0;
    std::ofstream(run / "checkpoint.json", std::ios::trunc) << checkpoint.dump();
    const std::map<std::string, std::string> before = runFiles(run);
    RunResult r = runCli(command + " --resume " + run.string(), scratch_);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("error: " + (run / "checkpoint.json").string() + ": values: media/fog/sigma_a[1] = 0, "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("log space"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << r.err;
    EXPECT_EQ(runFiles(run), before);
}

// A target without a camera is the scene's first camera's: naming that camera is the
// same run, so --resume accepts either spelling.
TEST_F(OptimizeResume, AResumeMayNameTheFirstCameraOfATargetOrLeaveItOut) {
    fs::path cut = scratch_ / "cut";
    ASSERT_EQ(runCli(command_ + " --out " + cut.string(), scratch_, kLoseDeviceMidRun).exitCode, 2);
    const std::string target = (scratch_ / "target.exr").string();
    std::string named = command_;
    named.replace(named.find(target), target.size(), "camera=" + target);
    RunResult resumed = runCli(named + " --resume " + cut.string(), scratch_);
    EXPECT_EQ(resumed.exitCode, 0) << resumed.err;
}

TEST_F(OptimizeResume, RefusesAResumeWithOtherOptionsOrAnotherOut) {
    fs::path cut = scratch_ / "cut";
    ASSERT_EQ(runCli(command_ + " --out " + cut.string(), scratch_, kLoseDeviceMidRun).exitCode, 2);
    std::string checkpoint = slurp(cut / "checkpoint.json");

    RunResult otherRate = runCli(command_ + " --lr 0.5 --resume " + cut.string(), scratch_);
    EXPECT_EQ(otherRate.exitCode, 2);
    EXPECT_NE(otherRate.err.find("learning_rate '0.01"), std::string::npos) << otherRate.err;
    RunResult otherSampling = runCli(command_ + " --no-equiangular --resume " + cut.string(), scratch_);
    EXPECT_EQ(otherSampling.exitCode, 2);
    EXPECT_NE(otherSampling.err.find("equiangular_sampling"), std::string::npos) << otherSampling.err;
    RunResult otherOut = runCli(command_ + " --resume " + cut.string() + " --out elsewhere", scratch_);
    EXPECT_EQ(otherOut.exitCode, 2);
    EXPECT_NE(otherOut.err.find("--out elsewhere"), std::string::npos) << otherOut.err;
    RunResult nothing = runCli(command_ + " --resume " + (scratch_ / "empty").string(), scratch_);
    EXPECT_EQ(nothing.exitCode, 2);
    EXPECT_NE(nothing.err.find("no checkpoint.json"), std::string::npos) << nothing.err;
    EXPECT_EQ(slurp(cut / "checkpoint.json"), checkpoint);
}

// The files a scene reads besides its glTF (here its density grid) decide the run as
// much as the glTF does: a checkpoint is refused once one of them has changed.
TEST_F(OptimizeResume, RefusesAResumeAfterAFileTheSceneReadsHasChanged) {
    const fs::path scenes = VKDR_TEST_SCENES_DIR;
    for (const char* file : {"cornell_plume.gltf", "cornell_plume.vdb"}) fs::copy_file(scenes / file, scratch_ / file);
    const std::string plume = (scratch_ / "cornell_plume.gltf").string();
    ASSERT_EQ(runCli("render " + plume + " --width 8 --height 8 --spp 2 --max-depth 2 -o " +
                         (scratch_ / "plume.exr").string(),
                     scratch_)
                  .exitCode,
              0);
    const std::string command = "optimize " + plume + " --target " + (scratch_ / "plume.exr").string() +
                                " --param media/plume/g --iters 2 --spp 1 --max-depth 2 --checkpoint-every 1";
    const fs::path run = scratch_ / "plume_run";
    RunResult first = runCli(command + " --out " + run.string(), scratch_);
    ASSERT_EQ(first.exitCode, 0) << first.err;
    ASSERT_TRUE(fs::exists(run / "checkpoint.json"));
    RunResult same = runCli(command + " --resume " + run.string(), scratch_);
    EXPECT_EQ(same.exitCode, 0) << same.err;

    fs::copy_file(scenes / "experiments" / "smoke_plume.vdb", scratch_ / "cornell_plume.vdb",
                  fs::copy_options::overwrite_existing);
    RunResult changed = runCli(command + " --resume " + run.string(), scratch_);
    EXPECT_EQ(changed.exitCode, 2) << changed.err;
    EXPECT_NE(changed.err.find("scene_files 'cornell_plume.vdb, 63890 bytes"), std::string::npos) << changed.err;
    EXPECT_EQ(changed.err.find("error: "), changed.err.rfind("error: ")) << changed.err;
}

// A log.jsonl that is not the checkpoint's run (another run's lines mixed in, lines
// lost, a loss edited) would make the resumed run's log a mixture: --resume refuses it.
TEST_F(OptimizeResume, RefusesALogThatDoesNotMatchTheCheckpoint) {
    fs::path cut = scratch_ / "cut";
    ASSERT_EQ(runCli(command_ + " --out " + cut.string(), scratch_, kLoseDeviceMidRun).exitCode, 2);
    const std::string checkpoint = slurp(cut / "checkpoint.json");
    std::vector<std::string> lines;
    std::istringstream log(slurp(cut / "log.jsonl"));
    for (std::string line; std::getline(log, line);) lines.push_back(line);
    ASSERT_GE(lines.size(), 2u);

    auto expectRefused = [&](const std::vector<std::string>& logLines, const std::string& what) {
        std::string text;
        for (const std::string& line : logLines) text += line + "\n";
        std::ofstream(cut / "log.jsonl", std::ios::trunc) << text;
        RunResult r = runCli(command_ + " --resume " + cut.string(), scratch_);
        EXPECT_EQ(r.exitCode, 2) << what << "\n" << r.err;
        EXPECT_NE(r.err.find("error: " + (cut / "log.jsonl").string()), std::string::npos) << what << "\n" << r.err;
        EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << r.err;
        EXPECT_EQ(r.err.find("iterations of"), std::string::npos) << "refused before the device is set up\n" << r.err;
        EXPECT_EQ(slurp(cut / "log.jsonl"), text) << what;
        EXPECT_EQ(slurp(cut / "checkpoint.json"), checkpoint) << what;
        EXPECT_FALSE(fs::exists(cut / "params.json")) << what;
    };
    std::vector<std::string> edited = lines;
    nlohmann::json first = nlohmann::json::parse(edited[0]);
    first["loss"] = first["loss"].get<double>() * 2.0;
    edited[0] = first.dump();
    expectRefused(edited, "a loss that differs");
    expectRefused({lines.begin() + 1, lines.end()}, "the first line missing");
    expectRefused({lines[0]}, "lines up to the checkpoint missing");
    expectRefused({}, "an empty log");
    std::vector<std::string> twice = {lines[0], lines[0]};
    twice.insert(twice.end(), lines.begin() + 1, lines.end());
    expectRefused(twice, "a line repeated");
    expectRefused({lines[0], "not json"}, "a damaged line");
    fs::remove(cut / "log.jsonl");
    RunResult missing = runCli(command_ + " --resume " + cut.string(), scratch_);
    EXPECT_EQ(missing.exitCode, 2) << missing.err;
    EXPECT_NE(missing.err.find("log.jsonl"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace vkdr::test
