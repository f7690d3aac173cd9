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
