#pragma once
#include <filesystem>
#include <functional>

#include "diff/loss_gradient.h"
#include "image/image.h"
#include "optimize/optimize_loop.h"
#include "optimize/run_identity.h"
#include "scene/scene.h"

namespace vkdr {

struct OptimizationJob {
    std::filesystem::path sceneFile;        // the glTF the scene came from; scene.gltf is a copy of it
    std::filesystem::path outputDirectory;  // created if missing
    OptimizeOptions options;
    LossKind loss = LossKind::L2;           // what the LossGradient computes; labels loss.svg
    Image firstTarget;                      // the first view's target, for diff.png
    RunInputs inputs;                       // what else decides the result, for the checkpoint's run identity
    bool resume = false;                    // continue from outputDirectory's checkpoint
};

struct OptimizationReport {
    OptimizeResult result;
    float largestDifference = 0.0f;  // the |render - target| that diff.png shows as white
};

// Optimises `scene` in place and writes into job.outputDirectory, every file atomically:
//   log.jsonl   after every iteration (optimize/iteration_log.h)
//   checkpoint.json every options.checkpointEvery iterations (optimize/checkpoint.h)
//   params.json the fitted values by name, scene.gltf the input scene with them written
//               back, final.exr/.png the last render of the first view, diff.png its
//               scaled difference to the target, loss.svg the loss curve.
// When the loop fails (optimize/optimize_loop.h) only log.jsonl, up to the last good
// iteration, and the last checkpoint are left: nothing that holds fitted values is written.
// Without job.resume it refuses a directory that holds another run's files
// (optimize/run_directory.h). With job.resume it reads the checkpoint, refuses it unless
// it was written by a run with the same identity and log.jsonl holds that run's lines up
// to it, drops the log's lines past it and continues from it: the outputs are those of
// the run that was never stopped. Interrupted by a signal, it leaves the log and a
// checkpoint of the last finished iteration (optimize/optimize_loop.h), and rethrows.
OptimizationReport runOptimization(LossGradient& lossGradient, Scene& scene, const OptimizationJob& job,
                                   const std::function<void(uint32_t iteration, double loss)>& progress = {});

}  // namespace vkdr
