#include "optimize/experiment_run.h"

#include "core/error.h"
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

std::vector<TargetView> renderTargets(const Experiment& experiment, const Scene& scene,
                                      const ExperimentBackend& backend) {
    std::vector<TargetView> targets;
    for (const std::string& camera : experiment.views) {
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

}  // namespace

OptimizationReport runExperiment(const Experiment& experiment, Scene& scene, const ExperimentBackend& backend,
                                 const std::filesystem::path& outputDirectory, bool resume,
                                 const std::function<void(uint32_t iteration, double loss)>& progress,
                                 const RunDescription& description) {
    prepareExperimentScene(experiment, scene);
    const std::vector<std::string>& names = experiment.optimize.parameters;

    applyValues(scene, experiment.trueValues);
    std::vector<std::vector<float>> truth = currentValues(scene, names);
    std::vector<TargetView> targets = renderTargets(experiment, scene, backend);
    applyValues(scene, experiment.startValues);

    OptimizationJob job{experiment.scene, outputDirectory, experiment.optimize, experiment.loss, targets};
    job.inputs = {experiment.file, {}, {}, experiment.render.spp, experiment.render.maxDepth};
    job.resume = resume;
    job.trueValues = truth;
    job.description = description;
    std::unique_ptr<LossGradient> lossGradient =
        backend.makeLossGradient(scene, targets, names, experiment.render, experiment.loss);
    OptimizationReport report = runOptimization(*lossGradient, scene, job, progress);
    writeExr(outputDirectory / "target.exr", targets[0].target);
    writePng(outputDirectory / "target.png", targets[0].target);
    return report;
}

}  // namespace vkdr
