#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "optimize/experiment.h"
#include "optimize/optimization_run.h"

namespace vkdr {

// What an experiment needs from a renderer; the command line provides Vulkan ones, so
// that this library needs no GPU.
struct ExperimentBackend {
    // Renders `scene` as `settings` say (camera by name, size, spp, seed): the targets.
    std::function<Image(const Scene& scene, const RenderSettings& settings)> render;
    // The loss and gradient of `scene`'s renders against `views` (each rendered at its
    // target's size) with respect to `parameters`.
    std::function<std::unique_ptr<LossGradient>(const Scene& scene, std::vector<TargetView> views,
                                                std::vector<std::string> parameters,
                                                const RenderSettings& settings, LossKind loss)>
        makeLossGradient;
};

// The targets render with the experiment's seed plus this, so that their noise is
// independent of every optimisation iteration's (seed + iteration).
inline constexpr uint32_t kTargetSeedOffset = 0x80000000u;
// Held-out views render with the experiment's seed plus this at every iteration: the
// same samples each time, so that their error changes only with the values.
inline constexpr uint32_t kHeldOutSeedOffset = 0x40000000u;

// Adds the experiment's cameras to `scene` (loaded from experiment.scene) and checks the
// experiment against it (prepareExperimentScene), then returns the job runExperiment
// gives runOptimization as it is before the targets are rendered, its run directory
// checked as runOptimization checks it (requireRunCanStart: refused before any target
// is rendered, and before a caller's device work) and its identity found. With `resume`
// the optimisation continues from the directory's checkpoint, which must come from the
// same experiment file, scene and settings. `replaceOldRun` is
// OptimizationJob::replaceOldRun; a caller may set the job's description.
OptimizationJob startExperiment(const Experiment& experiment, Scene& scene,
                                const std::filesystem::path& outputDirectory, bool resume = false,
                                const std::function<void()>& replaceOldRun = {});

// Renders the targets of `experiment` from the true values into `scene` (as
// startExperiment prepared it, with its `job`), resets to the start values and
// optimises, writing the outputs of runOptimization into the job's directory
// (report.html with the true values) plus target.exr/.png (the first view's target).
// Each iteration's record carries, as metrics, each held-out view's error
// (optimize/held_out_error.h) and each summarised parameter's relative L2 error against
// its true values. The report's parameters carry their true values.
OptimizationReport runExperiment(const Experiment& experiment, Scene& scene, const ExperimentBackend& backend,
                                 OptimizationJob job, const std::function<void(const IterationRecord&)>& progress = {});

}  // namespace vkdr
