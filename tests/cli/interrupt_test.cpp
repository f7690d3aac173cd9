// SIGINT and SIGTERM sent to a running command, as a user's Ctrl-C or a job scheduler
// sends them: the command stops, says so, exits with 128 + the signal's number, and
// leaves nothing half written; optimize leaves a checkpoint that --resume finishes from.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "running_cli.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

// Several lavapipe threads: gradients are fixed-point sums, the same bits in any order
// of addition, so a resumed run and an uninterrupted one agree to the bit all the same.
constexpr const char* kThreads = "LP_NUM_THREADS=4";

size_t lineCount(const fs::path& file) {
    std::istringstream text(slurp(file));
    size_t lines = 0;
    for (std::string line; std::getline(text, line);) ++lines;
    return lines;
}

bool holdsTemporaries(const fs::path& directory) {
    for (const auto& entry : fs::directory_iterator(directory)) {
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
    }
    return false;
}

class Interrupt : public CliScratchTest {
protected:
    fs::path target(int size) {
        fs::path file = dir_ / "target.exr";
        RunResult r = runCli("render " + fog() + " --width " + std::to_string(size) + " --height " +
                                 std::to_string(size) + " --spp 4 --max-depth 3 -o " + file.string(),
                             dir_);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return file;
    }

    bool printed(const std::string& text) const { return slurp(dir_ / "stderr").find(text) != std::string::npos; }

};

TEST_F(Interrupt, OptimizeCheckpointsItsLastFinishedIterationAndResumeEndsLikeAnUninterruptedRun) {
    std::string command = "optimize " + fog() + " --target " + target(16).string() +
                          " --param media/fog/sigma_a --iters 40 --spp 16 --max-depth 3 --checkpoint-every 1000";
    fs::path whole = dir_ / "whole", cut = dir_ / "cut";
    ASSERT_EQ(runCli(command + " --out " + whole.string(), dir_, kThreads).exitCode, 0);

    RunningCli running(command + " --out " + cut.string(), dir_, kThreads);
    ASSERT_TRUE(running.waitUntil([&] { return lineCount(cut / "log.jsonl") >= 1; })) << slurp(dir_ / "stderr");
    running.signal(SIGINT);
    RunResult stopped = running.finish();
    EXPECT_EQ(stopped.exitCode, 130) << stopped.err;
    EXPECT_EQ(stopped.err.find("error:"), std::string::npos) << stopped.err;
    EXPECT_NE(stopped.err.find("interrupted by SIGINT"), std::string::npos) << stopped.err;
    EXPECT_NE(stopped.err.find("run the same command with --resume " + cut.string()), std::string::npos)
        << stopped.err;
    for (const char* file : {"params.json", "scene.gltf", "final.exr", "loss.svg"}) {
        EXPECT_FALSE(fs::exists(cut / file)) << file;
    }
    EXPECT_FALSE(holdsTemporaries(cut));
    // Written although --checkpoint-every had not come round.
    nlohmann::json checkpoint = nlohmann::json::parse(slurp(cut / "checkpoint.json"));
    EXPECT_EQ(checkpoint["iteration"].get<size_t>(), lineCount(cut / "log.jsonl"));
    ASSERT_LT(checkpoint["iteration"].get<size_t>(), 40u) << "the run ended before the signal came";

    RunResult resumed = runCli(command + " --resume " + cut.string(), dir_, kThreads);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_EQ(slurp(cut / "params.json"), slurp(whole / "params.json"));
    EXPECT_EQ(lineCount(cut / "log.jsonl"), 40u);
}

// A resumed run renders the start values again for its report (iteration 0's renders
// were not kept): before its loop, so that a signal after the last iteration finds no
// render left to stop and the outputs are written.
TEST_F(Interrupt, ASignalAfterTheLastIterationOfAResumedRunLetsItWriteItsOutputs) {
    std::string command = "optimize " + fog() + " --target " + target(32).string() +
                          " --param media/fog/sigma_a --iters 2 --spp 64 --max-depth 3 --checkpoint-every 1";
    fs::path run = dir_ / "run";
    ASSERT_EQ(runCli(command + " --out " + run.string(), dir_, kThreads).exitCode, 0);
    ASSERT_EQ(nlohmann::json::parse(slurp(run / "checkpoint.json"))["iteration"].get<size_t>(), 1u);
    std::istringstream log(slurp(run / "log.jsonl"));
    std::string firstLine;
    std::getline(log, firstLine);
    std::ofstream(run / "log.jsonl", std::ios::trunc) << firstLine << "\n";
    for (const char* file : {"params.json", "final.exr", "scene.gltf"}) fs::remove(run / file);

    RunningCli running(command + " --resume " + run.string(), dir_, kThreads);
    ASSERT_TRUE(running.waitUntil([&] { return lineCount(run / "log.jsonl") >= 2; })) << slurp(dir_ / "stderr");
    running.signal(SIGINT);
    RunResult finished = running.finish();
    EXPECT_EQ(finished.err.find("error:"), std::string::npos) << finished.err;
    for (const char* file : {"params.json", "final.exr", "scene.gltf"}) {
        EXPECT_TRUE(fs::exists(run / file)) << file << "\n" << finished.err;
    }
}

TEST_F(Interrupt, OptimizeStoppedBeforeItsFirstIterationLeavesNoCheckpoint) {
    // 64x64 at 256 spp: the first iteration outlasts the signal by far.
    std::string command = "optimize " + fog() + " --target " + target(64).string() +
                          " --param media/fog/sigma_a --iters 5 --spp 256 --out " + (dir_ / "out").string();
    RunningCli running(command, dir_);
    ASSERT_TRUE(running.waitUntil([&] { return printed("iterations of adam"); })) << slurp(dir_ / "stderr");
    running.signal(SIGTERM);
    RunResult stopped = running.finish();
    EXPECT_EQ(stopped.exitCode, 143) << stopped.err;
    EXPECT_NE(stopped.err.find("interrupted by SIGTERM; no checkpoint had been written yet"), std::string::npos)
        << stopped.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "checkpoint.json"));
    EXPECT_FALSE(fs::exists(dir_ / "out" / "log.jsonl"));
}

// --overwrite removes the old run just before the new one's first write: stopped before
// then, the directory holds the old run whole, whose checkpoint this command would not
// resume, and the message says so instead of pointing at it.
TEST_F(Interrupt, OverwriteStoppedBeforeItsFirstWriteLeavesTheOldRunAndSaysSo) {
    const std::string targetFile = target(64).string();
    const fs::path out = dir_ / "out";
    ASSERT_EQ(runCli("optimize " + fog() + " --target " + targetFile +
                         " --param media/fog/g --iters 2 --spp 1 --max-depth 1 --checkpoint-every 1 --out " +
                         out.string(),
                     dir_)
                  .exitCode,
              0);
    const std::string oldCheckpoint = slurp(out / "checkpoint.json");
    fs::remove(dir_ / "stderr");  // the first run's, which says "iterations of adam" too
    RunningCli running("optimize " + fog() + " --target " + targetFile +
                           " --param media/fog/sigma_a --iters 5 --spp 256 --overwrite --out " + out.string(),
                       dir_);
    ASSERT_TRUE(running.waitUntil([&] { return printed("iterations of adam"); })) << slurp(dir_ / "stderr");
    running.signal(SIGINT);
    RunResult stopped = running.finish();
    EXPECT_EQ(stopped.exitCode, 130) << stopped.err;
    EXPECT_NE(stopped.err.find("this run had written nothing, and the run " + out.string() + " held is left as it was"),
              std::string::npos)
        << stopped.err;
    EXPECT_EQ(stopped.err.find("--resume"), std::string::npos) << stopped.err;
    EXPECT_EQ(slurp(out / "checkpoint.json"), oldCheckpoint);

    // Into a directory that held no run, there is no old run to speak of.
    fs::remove(dir_ / "stderr");
    RunningCli fresh("optimize " + fog() + " --target " + targetFile +
                         " --param media/fog/sigma_a --iters 5 --spp 256 --overwrite --out " + (dir_ / "new").string(),
                     dir_);
    ASSERT_TRUE(fresh.waitUntil([&] { return printed("iterations of adam"); })) << slurp(dir_ / "stderr");
    fresh.signal(SIGINT);
    RunResult freshStopped = fresh.finish();
    EXPECT_EQ(freshStopped.exitCode, 130) << freshStopped.err;
    EXPECT_NE(freshStopped.err.find("this run had written nothing"), std::string::npos) << freshStopped.err;
    EXPECT_EQ(freshStopped.err.find("left as it was"), std::string::npos) << freshStopped.err;
}

TEST_F(Interrupt, RenderStopsMidPassAndLeavesThePreviousFile) {
    fs::path out = dir_ / "out.exr";
    std::ofstream(out) << "previous result";
    // Hours of rendering at 64x64 and a million samples: only the signal ends it.
    RunningCli running("render " + fog() + " --width 64 --height 64 --spp 1000000 -o " + out.string(), dir_);
    ASSERT_TRUE(running.waitUntil([&] { return printed("triangles"); })) << slurp(dir_ / "stderr");
    running.signal(SIGINT);
    RunResult stopped = running.finish();
    EXPECT_EQ(stopped.exitCode, 130) << stopped.err;
    EXPECT_NE(stopped.err.find("interrupted by SIGINT"), std::string::npos) << stopped.err;
    EXPECT_EQ(stopped.out, "");
    EXPECT_EQ(slurp(out), "previous result");
    EXPECT_FALSE(holdsTemporaries(dir_));
}

TEST_F(Interrupt, GradStopsAndPrintsNoResult) {
    RunningCli running("grad " + fog() + " --target " + target(64).string() +
                           " --param media/fog/sigma_a --spp 1000000 --json",
                       dir_);
    // grad prints nothing before its result: wait until it handles the signal.
    ASSERT_TRUE(running.waitUntil([&] { return running.catches(SIGTERM); })) << slurp(dir_ / "stderr");
    running.signal(SIGTERM);
    RunResult stopped = running.finish();
    EXPECT_EQ(stopped.exitCode, 143) << stopped.err;
    EXPECT_EQ(stopped.out, "");
}

}  // namespace
}  // namespace vkdr::test
