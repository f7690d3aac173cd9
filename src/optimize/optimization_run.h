#pragma once
#include <filesystem>
#include <functional>
#include <optional>

#include "diff/loss_gradient.h"
#include "image/image.h"
#include "optimize/optimize_loop.h"
#include "optimize/parameter_table.h"
#include "optimize/run_identity.h"
#include "scene/scene.h"

namespace vkdr {

// How a run was started, for report.html.
struct RunDescription {
    std::string commandLine;  // as typed
    std::string device;       // the device's name
};

struct OptimizationJob {
    std::filesystem::path sceneFile;        // the glTF the scene came from; scene.gltf is a copy of it
    std::filesystem::path outputDirectory;  // created if missing
    OptimizeOptions options;
    LossKind loss = LossKind::L2;           // what the LossGradient computes; labels loss.svg
    std::vector<TargetView> targets;        // the LossGradient's views, in its order; diff.png shows the first
    RunInputs inputs;                       // what else decides the result, for the checkpoint's run identity
    bool resume = false;                    // continue from outputDirectory's checkpoint
    // The true value of each parameter, in options.parameters order, where known (an
    // experiment); empty otherwise. Shown in report.html.
    std::vector<std::vector<float>> trueValues;
    RunDescription description;
    std::vector<std::pair<std::string, std::string>> settings;  // more rows of report.html's settings: name, value
    // Figures measured at each iteration's values besides the loss (OptimizeCallbacks::measure):
    // logged, charted in report.html and shown by the progress callback.
    std::function<std::vector<Metric>(const Scene& scene, uint32_t iteration)> measure;
    // For --overwrite: removes the run the directory holds (optimize/run_directory.h).
    // Given, the directory may hold another run; it is called once, just before this run
    // writes its first file (log.jsonl, after iteration 0), so that a run that fails or
    // is stopped before then leaves the old one whole.
    std::function<void()> replaceOldRun;
    // Writes targets[0] as target.exr and target.png with the other outputs: an
    // experiment's target, which the run rendered and no file holds.
    bool writeTarget = false;
    // The run's identity (optimize/run_identity.h) as requireRunCanStart found it, so that
    // runOptimization does not read every file of the scene again; found there if not set.
    std::optional<RunIdentity> identity;
};

struct OptimizationReport {
    OptimizeResult result;
    float largestDifference = 0.0f;         // the |render - target| that diff.png shows as white
    std::vector<ParameterFit> parameters;   // start and fitted values (and true ones), in options.parameters order
};

// The checks runOptimization makes of job.outputDirectory before it writes anything: a
// new run's directory holds no other run's files (with job.replaceOldRun given, none of
// them is a directory); a resumed run's checkpoint is this run's and fits the scene, and
// log.jsonl holds that run's lines up to it; every density grid of the scene can be
// written back beside scene.gltf. Throws vkdr::Error as runOptimization
// would, and writes nothing: for a caller to make before its device work
// (runOptimization makes them again). Returns the run's identity, for job.identity.
RunIdentity requireRunCanStart(const OptimizationJob& job, const Scene& scene);

// Optimises `scene` in place and writes into job.outputDirectory, every file atomically:
//   log.jsonl   after every iteration (optimize/iteration_log.h)
//   checkpoint.json every options.checkpointEvery iterations (optimize/checkpoint.h)
//   params.json the fitted values by name (a summary for a parameter of many values), scene.gltf the input scene with them written
//               back, final.exr/.png the last render of the first view, diff.png its
//               scaled difference to the target, loss.svg the loss curve, and
//   report.html a page of all of it (optimize/report_html.h) for every view, with the
//               renders at the start values (for a resumed run, which did not render
//               them, one more evaluation at the start values with iteration 0's seed
//               gives the same images) and every parameter's trajectory from log.jsonl.
// When the loop fails (optimize/optimize_loop.h) only log.jsonl, up to the last good
// iteration, and the last checkpoint are left: nothing that holds fitted values is written.
// Without job.resume it refuses a directory that holds another run's files
// (optimize/run_directory.h). With job.resume it reads the checkpoint, refuses it unless
// it was written by a run with the same identity and log.jsonl holds that run's lines up
// to it, drops the log's lines past it and continues from it: the outputs are those of
// the run that was never stopped. Interrupted by a signal, it leaves the log and a
// checkpoint of the last finished iteration (optimize/optimize_loop.h), and rethrows.
// With options.smoothness or options.sparsity > 0 the loss optimised is
// `imageLossGradient`'s plus those priors of every density grid optimised
// (optimize/grid_priors.h).
OptimizationReport runOptimization(LossGradient& imageLossGradient, Scene& scene, const OptimizationJob& job,
                                   const std::function<void(const IterationRecord&)>& progress = {});

}  // namespace vkdr
