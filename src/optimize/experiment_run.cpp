#include "optimize/experiment_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

std::string joined(const std::vector<float>& values, const char* pattern) {
    std::string text;
    for (float value : values) {
        char number[32];
        std::snprintf(number, sizeof(number), pattern, double(value));
        text += (text.empty() ? "" : " ") + std::string(number);
    }
    return text;
}

std::string errors(const ParameterRecovery& recovery) {
    std::string text;
    for (size_t c = 0; c < recovery.recovered.size(); ++c) {
        double truth = recovery.truth[c], error = double(recovery.recovered[c]) - truth;
        char number[32];
        if (truth == 0.0) {
            std::snprintf(number, sizeof(number), "%+.3g abs", error);
        } else {
            std::snprintf(number, sizeof(number), "%+.2f%%", 100.0 * error / std::abs(truth));
        }
        text += (text.empty() ? "" : " ") + std::string(number);
    }
    return text;
}

}  // namespace

ExperimentResult runExperiment(const Experiment& experiment, Scene& scene, const ExperimentBackend& backend,
                               const std::filesystem::path& outputDirectory, bool resume,
                               const std::function<void(uint32_t iteration, double loss)>& progress) {
    prepareExperimentScene(experiment, scene);
    const std::vector<std::string>& names = experiment.optimize.parameters;

    applyValues(scene, experiment.trueValues);
    std::vector<std::vector<float>> truth = currentValues(scene, names);
    std::vector<TargetView> targets = renderTargets(experiment, scene, backend);
    applyValues(scene, experiment.startValues);
    std::vector<std::vector<float>> start = currentValues(scene, names);

    OptimizationJob job{experiment.scene, outputDirectory, experiment.optimize, experiment.loss, targets[0].target};
    job.inputs = {experiment.file, {}, {}, experiment.render.spp, experiment.render.maxDepth};
    job.resume = resume;
    std::unique_ptr<LossGradient> lossGradient =
        backend.makeLossGradient(scene, targets, names, experiment.render, experiment.loss);
    ExperimentResult result;
    result.report = runOptimization(*lossGradient, scene, job, progress);
    writeExr(outputDirectory / "target.exr", job.firstTarget);
    writePng(outputDirectory / "target.png", job.firstTarget);

    for (size_t i = 0; i < names.size(); ++i) {
        result.recoveries.push_back({names[i], truth[i], start[i], getParameter(scene, names[i])});
    }
    return result;
}

std::string recoveryTable(const std::vector<ParameterRecovery>& recoveries) {
    size_t nameWidth = std::string("parameter").size();
    for (const ParameterRecovery& recovery : recoveries) nameWidth = std::max(nameWidth, recovery.name.size());
    char line[512];
    std::snprintf(line, sizeof(line), "%-*s  %-26s  %-26s  %-26s  %s\n", int(nameWidth), "parameter", "true", "start",
                  "recovered", "error");
    std::string table = line;
    for (const ParameterRecovery& recovery : recoveries) {
        std::snprintf(line, sizeof(line), "%-*s  %-26s  %-26s  %-26s  %s\n", int(nameWidth), recovery.name.c_str(),
                      joined(recovery.truth, "%.4g").c_str(), joined(recovery.start, "%.4g").c_str(),
                      joined(recovery.recovered, "%.5g").c_str(), errors(recovery).c_str());
        table += line;
    }
    return table;
}

}  // namespace vkdr
