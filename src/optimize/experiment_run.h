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

// The job runExperiment gives runOptimization, as it is before the targets are rendered:
// without them, the true values, the held-out views' settings and measures and the run's
// description, but enough for requireRunCanStart.
OptimizationJob experimentJob(const Experiment& experiment, const std::filesystem::path& outputDirectory, bool resume,
                              const std::function<void()>& replaceOldRun = {});

// Checks `experiment` against `scene` (loaded from experiment.scene), renders the targets
// from the true values, resets to the start values and optimises, writing the outputs of
// runOptimization into `outputDirectory` (report.html with the true values) plus
// target.exr/.png (the first view's target). Each iteration's record carries, as
// metrics, each held-out view's error (optimize/held_out_error.h) and each summarised
// parameter's relative L2 error against its true values.
// With `resume` the optimisation continues from the directory's checkpoint, which must
// come from the same experiment file, scene and settings. The directory is refused as
// runOptimization refuses it (requireRunCanStart) before any target is rendered.
// The report's parameters carry their true values. `replaceOldRun` is
// OptimizationJob::replaceOldRun.
OptimizationReport runExperiment(const Experiment& experiment, Scene& scene, const ExperimentBackend& backend,
                                 const std::filesystem::path& outputDirectory, bool resume = false,
                                 const std::function<void(const IterationRecord&)>& progress = {},
                                 const RunDescription& description = {},
                                 const std::function<void()>& replaceOldRun = {});

}  // namespace vkdr
