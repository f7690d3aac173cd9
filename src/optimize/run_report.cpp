#include "optimize/run_report.h"

#include <algorithm>

#include "core/format_text.h"
#include "optimize/iteration_log.h"
#include "optimize/loss_kind_text.h"

namespace vkdr {
namespace {

std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

std::vector<std::pair<std::string, std::string>> settings(const OptimizationJob& job, const OptimizeResult& result,
                                                          double seconds) {
    const OptimizeOptions& options = job.options;
    std::vector<std::string> cameras;
    for (const TargetView& view : job.targets) cameras.push_back(view.camera.empty() ? "(first camera)" : view.camera);
    std::vector<std::pair<std::string, std::string>> rows = {
        {"views", listed(cameras)},
        {"parameters", listed(options.parameters)},
        {"iterations", std::to_string(options.iterations)},
        {"optimizer", optimizerKindName(options.optimizer)},
        {"learning rate", formatText("%g", options.learningRate)},
    };
    if (!job.inputs.experiment.empty()) rows.insert(rows.begin(), {"experiment", job.inputs.experiment.string()});
    for (const auto& [name, rate] : options.learningRates) {
        rows.push_back({"learning rate of " + name, formatText("%g", rate)});
    }
    if (options.optimizer == OptimizerKind::Adam && options.adamEpsilon != OptimizeOptions{}.adamEpsilon) {
        rows.push_back({"Adam epsilon", formatText("%g", options.adamEpsilon)});
    }
    if (options.learningRateDecay != 1.0) {
        rows.push_back({"learning rate decay", formatText("to %g of the rate, starting %g of the way through",
                                                         options.learningRateDecay, options.learningRateDecayStart)});
    }
    if (!options.logParameters.empty()) rows.push_back({"stepped in log space", listed(options.logParameters)});
    rows.push_back({"samples per pixel", std::to_string(job.inputs.spp)});
    rows.push_back({"max depth", std::to_string(job.inputs.maxDepth)});
    rows.push_back({"loss", lossKindName(job.loss)});
    rows.push_back({"seed", std::to_string(options.seed) + " (iteration i renders with seed + i)"});
    rows.insert(rows.end(), job.settings.begin(), job.settings.end());
    if (options.smoothness != 0.0) {
        rows.push_back({"smoothness", formatText("%g times the mean squared difference of face neighbours, on "
                                                 "every density grid (in the loss)", options.smoothness)});
    }
    if (options.sparsity != 0.0) {
        rows.push_back({"sparsity", formatText("%g times the mean density, on every density grid (in the loss)",
                                               options.sparsity)});
    }
    if (options.totalVariation != 0.0) {
        rows.push_back({"total variation", formatText("%g times the mean absolute difference of face neighbours, on "
                                                      "every density grid (in the loss)", options.totalVariation)});
    }
    if (options.gridLevels > 1) {
        rows.push_back({"coarse-to-fine", formatText("%u levels: density grid steps restricted to a grid %u times "
                                                     "coarser at first, halved every %g iterations",
                                                     options.gridLevels, 1u << (options.gridLevels - 1),
                                                     double(options.iterations) / options.gridLevels)});
    }
    if (!job.description.device.empty()) rows.push_back({"device", job.description.device});
    // Per iteration in milliseconds as well, as `optimize` prints it: a short run's totals
    // round to 0.0 s.
    const double iterations = double(std::max<size_t>(result.losses.size(), 1));
    rows.push_back({"render time", formatText("%.1f s forward, %.1f s adjoint over all %zu iterations (%.1f ms and "
                                             "%.1f ms per iteration)",
                                             result.forwardMs / 1000.0, result.adjointMs / 1000.0,
                                             result.losses.size(), result.forwardMs / iterations,
                                             result.adjointMs / iterations)});
    rows.push_back({"time taken", formatText(job.resume ? "%.1f s (this resumed part of the run)" : "%.1f s",
                                            seconds)});
    return rows;
}

}  // namespace

ReportPage runReportPage(const OptimizationJob& job, const OptimizationReport& report,
                         std::vector<Image> startImages, double seconds) {
    ReportPage page;
    page.commandLine = job.description.commandLine;
    page.scene = job.sceneFile.string();
    page.settings = settings(job, report.result, seconds);
    for (size_t i = 0; i < job.targets.size(); ++i) {
        page.views.push_back({job.targets[i].camera, job.targets[i].target, std::move(startImages.at(i)),
                              report.result.lastImages.at(i)});
    }
    page.losses = report.result.losses;
    page.lossName = lossKindName(job.loss);
    page.fits = report.parameters;
    page.trajectories = readTrajectories(job.outputDirectory / kLogFileName, job.options.parameters);
    page.metrics = readMetrics(job.outputDirectory / kLogFileName);
    return page;
}

}  // namespace vkdr
