#include "optimize/optimization_run.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/process_start.h"
#include "image/atomic_write.h"
#include "optimize/checkpoint.h"
#include "optimize/difference_image.h"
#include "optimize/grid_priors.h"
#include "optimize/iteration_log.h"
#include "optimize/json_numbers.h"
#include "optimize/loss_chart.h"
#include "optimize/loss_kind_text.h"
#include "optimize/parameter_vector.h"
#include "optimize/report_html.h"
#include "optimize/run_directory.h"
#include "optimize/run_report.h"
#include "optimize/value_summary.h"
#include "scene/gltf_diagnostics.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "scene/write_scene.h"

namespace vkdr {
namespace {

void writeText(const std::filesystem::path& file, const std::string& text) {
    writeAtomically(file, [&](std::ofstream& stream) { stream << text; });
}

// Each parameter's fitted values; one of many values (a texture, a grid) as its summary,
// its values being in scene.gltf and the files beside it.
std::string parametersJson(const Scene& scene, const std::vector<std::string>& names) {
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const std::string& name : names) {
        std::vector<float> value = getParameter(scene, name);
        if (isSummarised(value.size())) {
            values[name] = summaryJson(summarise(value));
            values[name]["values_in"] = "scene.gltf";
        } else {
            values[name] = floatArray(value);
        }
    }
    return values.dump(2) + "\n";
}

// Which fitted values params.json holds, for a run whose scene.gltf could not be written:
// the summarised ones (a texture's, a grid's) were to be in its files.
std::string heldByParametersJson(const Scene& scene, const std::vector<std::string>& names) {
    std::string summarised;
    size_t count = 0;
    for (const std::string& name : names) {
        if (isSummarised(getParameter(scene, name).size())) summarised += (count++ ? ", " : "") + name;
    }
    if (count == 0) return " (params.json holds the fitted values)";
    if (count == names.size()) return " (params.json only summarises the fitted values; they are not written)";
    return " (params.json holds the fitted values but for " + summarised +
           ", which it only summarises; their fitted values are not written)";
}

void createDirectory(const std::filesystem::path& directory) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error || !std::filesystem::is_directory(directory)) {
        throw Error("cannot create output directory '" + directory.string() + "': " +
                    (error ? error.message() : "a file of that name exists"));
    }
}

// A checkpoint from a run with the same identity fits unless the file was edited.
void requireFits(const std::filesystem::path& file, const LoopState& state, const OptimizeOptions& options,
                 const Scene& scene) {
    auto fail = [&](const std::string& problem) { throw Error(file.string() + ": " + problem); };
    ParameterVector parameters(scene, options.parameters);
    const size_t valueCount = parameters.size();
    if (state.iteration == 0 || state.iteration >= options.iterations) {
        fail("iteration " + std::to_string(state.iteration) + " is not within the run's " +
             std::to_string(options.iterations) + " iterations");
    }
    if (state.losses.size() != state.iteration) fail("losses: expected one per iteration done");
    // Either optimiser takes one step per iteration; Adam's bias correction counts them.
    if (state.optimizer.steps != state.iteration) {
        fail("optimizer.steps: expected " + std::to_string(state.iteration) + ", one per iteration done");
    }
    if (state.values.size() != valueCount) fail("values: expected " + std::to_string(valueCount));
    size_t moments = options.optimizer == OptimizerKind::Adam ? valueCount : 0;
    if (state.optimizer.mean.size() != moments || state.optimizer.meanSquare.size() != moments) {
        fail("optimizer: expected " + std::to_string(moments) + " moments of each kind");
    }
    // A hand-edited value outside its parameter's range is refused here, naming the file,
    // not later by the scene: projecting it into the range would change it. So is one
    // that log space cannot start from (LogSpace::leave keeps a run's values above 0).
    std::copy(state.values.begin(), state.values.end(), parameters.values().begin());
    parameters.project();
    for (size_t i = 0; i < parameters.names().size(); ++i) {
        const std::string& name = parameters.names()[i];
        const bool inLogSpace =
            std::find(options.logParameters.begin(), options.logParameters.end(), name) != options.logParameters.end();
        for (size_t c = 0; c < parameters.count(i); ++c) {
            const size_t at = parameters.offset(i) + c;
            const std::string value = "values: " + name + "[" + std::to_string(c) + "] = " +
                                      formatNumber(state.values[at]);
            if (parameters.values()[at] != state.values[at]) fail(value + " is outside the parameter's range");
            if (inLogSpace && !(state.values[at] > 0.0)) {
                fail(value + ", where the run steps the parameter in log space, which needs every value positive");
            }
        }
    }
}

std::optional<LoopState> resumeState(const OptimizationJob& job, const Scene& scene, const RunIdentity& identity) {
    if (!job.resume) {
        requireRunDirectoryFor(job.outputDirectory, job.replaceOldRun ? RunStart::Overwrite : RunStart::New);
        return std::nullopt;
    }
    requireRunDirectoryFor(job.outputDirectory, RunStart::Resume);
    std::filesystem::path file = job.outputDirectory / kCheckpointFileName;
    Checkpoint checkpoint = readCheckpoint(file);
    requireSameRun(file, checkpoint.run, identity);
    requireFits(file, checkpoint.state, job.options, scene);
    return checkpoint.state;
}

std::vector<std::vector<float>> currentValues(const Scene& scene, const std::vector<std::string>& names) {
    std::vector<std::vector<float>> values;
    for (const std::string& name : names) values.push_back(getParameter(scene, name));
    return values;
}

// The run's identity, the files its scene reads besides the glTF included.
RunIdentity identityOf(const OptimizationJob& job, const Scene& scene) {
    RunIdentity identity = runIdentity(job.sceneFile, job.options, job.loss, job.inputs);
    addSceneFiles(identity, scene);
    return identity;
}

}  // namespace

RunIdentity requireRunCanStart(const OptimizationJob& job, const Scene& scene) {
    requireWritableDensityGrids(scene);  // the run ends by writing them
    const RunIdentity identity = identityOf(job, scene);
    std::optional<LoopState> resume = resumeState(job, scene, identity);
    if (resume) resumedLogLines(job.outputDirectory / kLogFileName, resume->losses);
    return identity;
}

OptimizationReport runOptimization(LossGradient& imageLossGradient, Scene& scene, const OptimizationJob& job,
                                   const std::function<void(const IterationRecord&)>& progress) {
    std::map<std::string, GridPriorWeights> priors =
        gridPriorWeights(job.options.parameters, gridPriorWeightsOf(job.options));
    std::optional<GridPriorLossGradient> withPriors;
    if (!priors.empty()) withPriors.emplace(imageLossGradient, std::move(priors));
    LossGradient& lossGradient = withPriors ? static_cast<LossGradient&>(*withPriors) : imageLossGradient;
    const std::filesystem::path& directory = job.outputDirectory;
    const std::vector<std::string>& names = job.options.parameters;
    const RunIdentity identity = job.identity ? *job.identity : identityOf(job, scene);
    std::optional<LoopState> resume = resumeState(job, scene, identity);
    requireWritableDensityGrids(scene);
    createDirectory(directory);
    removeStaleTemporaries(directory);  // a killed run's partial writes
    IterationLog log = resume ? IterationLog(directory / kLogFileName, resume->losses)
                              : IterationLog(directory / kLogFileName);
    // What goes when this run writes its first file, so that a run that fails or is
    // stopped before then leaves the directory as it was: another run's files (with
    // --overwrite), or a resumed run's outputs, which the iterations it takes again
    // replace (its log and checkpoint are rewritten in place).
    std::function<void()> replaceOldRun = job.replaceOldRun;
    if (resume) replaceOldRun = [&] { removeRunOutputs(directory, job.writeTarget); };
    auto writing = [&] {
        if (replaceOldRun) std::exchange(replaceOldRun, {})();
    };
    OptimizeCallbacks callbacks;
    callbacks.measure = job.measure;
    callbacks.iterationDone = [&](const IterationRecord& record) {
        // The log is the run's first file (no checkpoint precedes iteration 0's line): it
        // is complete in its temporary before the old run's files go, so that a write that
        // fails leaves the old run whole.
        PendingRenames pending;
        log.append(record, &pending);
        writing();
        pending.commit();
        if (progress) progress(record);
    };
    callbacks.checkpoint = [&](const LoopState& state) {
        writing();
        writeCheckpoint(directory / kCheckpointFileName, {identity, state});
    };

    OptimizationReport report;
    // The scene holds the start values until optimize() writes a resumed run's into it.
    std::vector<std::vector<float>> start = currentValues(scene, names);
    // The renders at the start values that iteration 0 made, for the report: a resumed
    // run did not keep them and renders them again with iteration 0's seed, which gives
    // the same images. Before the loop, so that a signal after its last iteration still
    // lets the outputs be written.
    std::vector<Image> resumedStartRenders;
    if (resume) resumedStartRenders = lossGradient.evaluate(scene, job.options.seed).images;
    report.result = optimize(lossGradient, scene, job.options, callbacks, resume ? &*resume : nullptr);
    std::vector<std::vector<float>> fitted = currentValues(scene, names);
    for (size_t i = 0; i < names.size(); ++i) {
        report.parameters.push_back({names[i], start[i], fitted[i], i < job.trueValues.size() ? job.trueValues[i]
                                                                                              : std::vector<float>{}});
    }
    const Image& finalImage = report.result.lastImages.at(0);
    DifferenceImage difference = scaledDifference(finalImage, job.targets.at(0).target);
    report.largestDifference = difference.largestDifference;
    std::vector<Image> startRenders =
        report.result.firstImages.empty() ? std::move(resumedStartRenders) : report.result.firstImages;

    writing();
    writeText(directory / "params.json", parametersJson(scene, job.options.parameters));
    writeExr(directory / "final.exr", finalImage);
    writePng(directory / "final.png", finalImage);
    writePng(directory / "diff.png", difference.image);
    writeText(directory / "loss.svg", lossChartSvg(report.result.losses, lossKindName(job.loss)));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - kProcessStart).count();
    writeText(directory / "report.html", reportHtml(runReportPage(job, report, std::move(startRenders), seconds)));
    if (job.writeTarget) {
        writeExr(directory / "target.exr", job.targets.at(0).target);
        writePng(directory / "target.png", job.targets.at(0).target);
    }
    // Last: it reads the scene file again, which may have changed during a long run
    // (scene/write_scene.h refuses that), and the other outputs stand without it.
    try {
        writeSceneWithParameters(job.sceneFile, scene, directory / "scene.gltf");
    } catch (const Error& error) {
        throw Error(std::string(error.what()) + "; scene.gltf is not written, and the run's other outputs are in " +
                    directory.string() + heldByParametersJson(scene, names));
    }
    return report;
}

}  // namespace vkdr
