#include "optimize/experiment_run.h"

#include "core/error.h"
#include "core/format_text.h"
#include "optimize/held_out_error.h"
#include "optimize/value_summary.h"
#include "image/finite_pixels.h"
#include "scene/parameters.h"

namespace vkdr {
namespace {

void applyValues(Scene& scene, const std::vector<ParameterValue>& values) {
    for (const ParameterValue& value : values) {
        setParameter(scene, value.name, value.values);
    }
}

std::vector<std::vector<float>> currentValues(const Scene& scene, const std::vector<std::string>& names) {
    std::vector<std::vector<float>> values;
    for (const std::string& name : names) values.push_back(getParameter(scene, name));
    return values;
}

std::vector<TargetView> renderTargets(const Experiment& experiment, const std::vector<std::string>& cameras,
                                      const Scene& scene, const ExperimentBackend& backend) {
    std::vector<TargetView> targets;
    for (const std::string& camera : cameras) {
        RenderSettings settings = experiment.render;
        settings.camera = camera;
        settings.spp = experiment.targetSpp;
        settings.seed = experiment.optimize.seed + kTargetSeedOffset;
        Image target = backend.render(scene, settings);
        if (std::optional<std::string> pixel = unrepresentablePixel(target)) {
            throw Error(experiment.file.string() + ": the target rendered from the true values for camera '" +
                        camera + "': " + *pixel);
        }
        targets.push_back({camera, std::move(target)});
    }
    return targets;
}

// A held-out view: its target, and the true scene rendered with the samples every
// iteration's render of it uses (experiment seed + kHeldOutSeedOffset, the fit's spp).
struct HeldOutView {
    TargetView target;
    RenderSettings settings;
    Image trueRender;
};

std::vector<HeldOutView> heldOutViews(const Experiment& experiment, const Scene& trueScene,
                                      const ExperimentBackend& backend) {
    std::vector<HeldOutView> views;
    std::vector<TargetView> targets = renderTargets(experiment, experiment.heldOutViews, trueScene, backend);
    for (TargetView& target : targets) {
        if (!(targetMean(target.target) > 0.0)) {
            throw Error(experiment.file.string() + ": held_out_views: the target of camera '" + target.camera +
                        "' is black (nothing it sees is lit), so no error is relative to it; hold out another view");
        }
        RenderSettings settings = experiment.render;
        settings.camera = target.camera;
        settings.seed = experiment.optimize.seed + kHeldOutSeedOffset;
        Image trueRender = backend.render(trueScene, settings);
        if (std::optional<std::string> pixel = unrepresentablePixel(trueRender)) {
            throw Error(experiment.file.string() + ": the held-out view '" + target.camera +
                        "' rendered from the true values: " + *pixel);
        }
        views.push_back({std::move(target), settings, std::move(trueRender)});
    }
    return views;
}

// Each held-out view's error and each summarised parameter's error against its true
// values, at an iteration's values.
std::vector<Metric> experimentMetrics(const Scene& scene, const std::vector<HeldOutView>& heldOut,
                                      const ExperimentBackend& backend, const std::vector<std::string>& names,
                                      const std::vector<std::vector<float>>& truth) {
    std::vector<Metric> metrics;
    for (const HeldOutView& view : heldOut) {
        Image render = backend.render(scene, view.settings);
        if (std::optional<std::string> pixel = unrepresentablePixel(render)) {
            throw Error("held-out view '" + view.target.camera + "' rendered at the fit's values: " + *pixel);
        }
        HeldOutError error = heldOutError(render, view.trueRender, view.target.target);
        metrics.push_back({"held-out " + view.target.camera + " relative RMSE", error.relativeRmse});
        metrics.push_back({"held-out " + view.target.camera + " excess error (standard errors)",
                           error.excessInStandardErrors});
    }
    for (size_t i = 0; i < names.size(); ++i) {
        std::vector<float> values = getParameter(scene, names[i]);
        if (!isSummarised(values.size())) continue;
        if (std::optional<double> error = relativeL2Error(values, truth[i])) {
            metrics.push_back({names[i] + " relative L2 error", *error});
        }
    }
    return metrics;
}

std::vector<std::pair<std::string, std::string>> heldOutSettings(const std::vector<HeldOutView>& heldOut) {
    std::vector<std::pair<std::string, std::string>> rows;
    for (const HeldOutView& view : heldOut) {
        HeldOutError floor = heldOutError(view.trueRender, view.trueRender, view.target.target);
        rows.push_back({"held-out view " + view.target.camera,
                        formatText("not fitted; the true scene rendered with the same samples is %.4g from its "
                                   "target (relative RMSE), the noise floor a perfect fit reaches",
                                   floor.relativeRmse)});
    }
    return rows;
}

}  // namespace

OptimizationJob startExperiment(const Experiment& experiment, Scene& scene,
                                const std::filesystem::path& outputDirectory, bool resume,
                                const std::function<void()>& replaceOldRun) {
    prepareExperimentScene(experiment, scene);
    OptimizationJob job{experiment.scene, outputDirectory, experiment.optimize, experiment.loss, {}};
    job.inputs = {experiment.file, {}, {}, experiment.render.spp, experiment.render.maxDepth,
                  experiment.render.equiangularSampling};
    job.resume = resume;
    job.replaceOldRun = replaceOldRun;
    job.identity = requireRunCanStart(job, scene);
    return job;
}

OptimizationReport runExperiment(const Experiment& experiment, Scene& scene, const ExperimentBackend& backend,
                                 OptimizationJob job, const std::function<void(const IterationRecord&)>& progress) {
    const std::vector<std::string>& names = experiment.optimize.parameters;
    applyValues(scene, experiment.trueValues);
    std::vector<std::vector<float>> truth = currentValues(scene, names);
    std::vector<TargetView> targets = renderTargets(experiment, experiment.views, scene, backend);
    std::vector<HeldOutView> heldOut = heldOutViews(experiment, scene, backend);
    applyValues(scene, experiment.startValues);

    job.targets = targets;
    job.writeTarget = true;
    job.trueValues = truth;
    job.settings = heldOutSettings(heldOut);
    job.measure = [&](const Scene& current, uint32_t) {
        return experimentMetrics(current, heldOut, backend, names, truth);
    };
    std::unique_ptr<LossGradient> lossGradient =
        backend.makeLossGradient(scene, targets, names, experiment.render, experiment.loss);
    return runOptimization(*lossGradient, scene, job, progress);
}

}  // namespace vkdr
