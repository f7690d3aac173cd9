#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "bvh/bvh.h"
#include "cli/commands.h"
#include "cli/experiment_backend.h"
#include "cli/install_layout.h"
#include "cli/iteration_progress.h"
#include "cli/number_options.h"
#include "image/output_paths.h"
#include "optimize/density_grid_options.h"
#include "cli/progress_bar.h"
#include "cli/sampling_options.h"
#include "cli/scene_options.h"
#include "cli/target_views.h"
#include "cli/warnings.h"
#include "core/error.h"
#include "core/format_text.h"
#include "core/interrupt.h"
#include "diff/rendered_loss_gradient.h"
#include "image/image.h"
#include "optimize/checkpoint.h"
#include "optimize/coarse_grid_gradient.h"
#include "optimize/experiment_run.h"
#include "optimize/grid_priors.h"
#include "optimize/log_space.h"
#include "optimize/loss_kind_text.h"
#include "optimize/optimization_run.h"
#include "optimize/parameter_table.h"
#include "optimize/parameter_vector.h"
#include "optimize/run_directory.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "scene/scene_warnings.h"
#include "vk/context.h"
#include "vk/vulkan.h"

namespace vkdr {
namespace {

struct OptimizeCommandOptions {
    SceneOptions scene;
    std::vector<std::string> targets;  // FILE or CAMERA=FILE
    std::vector<std::string> parameters;
    std::string experiment;
    OptimizeOptions optimize;
    RenderSettings settings;
    std::string optimizer = "adam";
    std::string loss = "l2";
    std::string out = "optimize-out";
    std::string resume;  // a previous run's --out directory to continue in
    bool overwrite = false;  // replace the run that --out holds
    // Set once --overwrite has removed the old run (just before this run's first write).
    std::shared_ptr<bool> oldRunRemoved = std::make_shared<bool>(false);
    std::string device;
    std::string commandLine;  // as typed, for report.html
};

// The options an experiment file also sets; given on the command line, they win.
struct ExperimentOverrides {
    CLI::Option* iterations;
    CLI::Option* learningRate;
    CLI::Option* learningRateDecay;
    CLI::Option* learningRateDecayStart;
    CLI::Option* logParameters;
    CLI::Option* adamEpsilon;
    CLI::Option* optimizer;
    CLI::Option* smoothness;
    CLI::Option* sparsity;
    CLI::Option* totalVariation;
    CLI::Option* gridLevels;
    CLI::Option* spp;
    CLI::Option* maxDepth;
    CLI::Option* loss;
    CLI::Option* seed;
};

// --resume DIR continues the run whose outputs are in DIR, and writes there.
void applyResume(OptimizeCommandOptions& options, const CLI::Option* outGiven) {
    if (options.resume.empty()) return;
    if (options.overwrite) {
        throw Error("--overwrite starts a new run and --resume " + options.resume + " continues one; give one of them");
    }
    if (outGiven->count() && !sameFile(options.out, options.resume)) {
        throw Error("--resume " + options.resume + " writes into that directory; drop --out " + options.out);
    }
    options.out = options.resume;
}

RunStart runStart(const OptimizeCommandOptions& options) {
    return !options.resume.empty() ? RunStart::Resume : options.overwrite ? RunStart::Overwrite : RunStart::New;
}

// The files a run writes into its directory (and --overwrite removes) must not be ones
// it reads: `optimize scene.gltf --out .` would replace the user's scene. An input is
// checked as named and as the file its symbolic links lead to, which the run's writes
// would replace as well.
void requireRunWritesNoInput(const std::filesystem::path& directory, bool experiment,
                             const std::vector<NamedOutput>& inputs) {
    for (const NamedOutput& input : inputs) {
        std::error_code unresolved;
        const std::filesystem::path resolved = std::filesystem::weakly_canonical(input.path, unresolved);
        for (const std::filesystem::path& path : {input.path, unresolved ? input.path : resolved}) {
            const std::filesystem::path parent = path.parent_path().empty() ? "." : path.parent_path();
            if (isRunFileName(path.filename().string(), experiment) && sameFile(parent, directory)) {
                const std::string leadsTo = path == input.path ? "" : " (a link to " + path.string() + ")";
                throw Error("--out " + directory.string() + ": the run writes " + path.filename().string() +
                            " there, which is " + input.option + " " + input.path.string() + leadsTo +
                            "; give another --out");
            }
        }
    }
}

// Before any work: the directory can be written, and holds no other run unless told. A
// run file there that is the run's own SCENE or experiment file is named as such first:
// it is no other run, and --overwrite would not help.
void requireRunDirectory(const OptimizeCommandOptions& options) {
    requireOutputDirectory(options.resume.empty() ? "--out" : "--resume", options.out);
    const bool experiment = !options.experiment.empty();
    if (experiment) {
        requireRunWritesNoInput(options.out, true, {{"--experiment", options.experiment}});
    } else if (!options.scene.file.empty()) {
        requireRunWritesNoInput(options.out, false, {{"SCENE", options.scene.file}});
    }
    requireRunDirectoryFor(options.out, runStart(options), experiment);
}

std::vector<NamedOutput> filesTheSceneReads(const LoadedScene& loaded) {
    std::vector<NamedOutput> files;
    for (const std::filesystem::path& file : loaded.externalFiles) files.push_back({"a file the scene reads", file});
    return files;
}

// With --overwrite, nothing of the old run is left for the new one to mix with; the
// files go just before the new run writes its first, so a run that fails before then
// leaves the old one whole.
std::function<void()> oldRunRemover(const OptimizeCommandOptions& options, bool experiment) {
    if (!options.overwrite) return {};
    return [out = options.out, experiment, removed = options.oldRunRemoved] {
        removeRunFiles(out, experiment);
        *removed = true;
    };
}

void printOutputs(const std::filesystem::path& directory, const OptimizationReport& report, bool experiment) {
    const OptimizeResult& result = report.result;
    warnOfCutPaths(result.truncatedPaths, "the renders of the iterations run");
    std::printf("%s", parameterTable(report.parameters).c_str());
    double iterations = double(result.losses.size());
    // A resumed run's forward and adjoint times include the checkpoint's iterations; its
    // wall clock only those this process ran.
    const std::string ranHere = result.iterationsRun == result.losses.size()
                                    ? ""
                                    : formatText(" over the %u iterations run since the checkpoint",
                                                 result.iterationsRun);
    std::printf("final loss %.6g after %zu iterations; per iteration %.1f ms forward, %.1f ms adjoint, "
                "%.1f ms in all%s\n",
                result.losses.back(), result.losses.size(), result.forwardMs / iterations,
                result.adjointMs / iterations, result.iterationMs / std::max(1u, result.iterationsRun),
                ranHere.c_str());
    if (!result.lastMetrics.empty()) std::printf("last iteration%s\n", metricsText(result.lastMetrics).c_str());
    std::printf("diff.png: white is an absolute difference of %.4g\n", double(report.largestDifference));
    // The directory holds this run's files alone (a new run's held none; --overwrite
    // removed the old run's; --resume continues the run it holds).
    std::string written;
    for (const std::string& name : presentRunFiles(directory, experiment)) {
        written += (written.empty() ? "" : ", ") + name;
    }
    std::printf("wrote %s to %s\n", written.c_str(), directory.string().c_str());
}

// With --overwrite, before this run wrote its first file: that the run the directory held
// is left as it was (empty where it held none).
std::string oldRunKept(const OptimizeCommandOptions& options) {
    const std::filesystem::path directory = options.out;
    const bool heldARun = !presentRunFiles(directory, !options.experiment.empty()).empty();
    return heldARun ? "the run " + directory.string() + " held is left as it was" : std::string();
}

// What the run directory holds to resume from, for the message that ends a stopped run.
// With --overwrite, until this run wrote its first file the directory holds the old run
// whole: its checkpoint is that run's, which this command would not resume.
std::string resumeHint(const OptimizeCommandOptions& options) {
    const std::filesystem::path directory = options.out;
    if (options.overwrite && !*options.oldRunRemoved) {
        const std::string kept = oldRunKept(options);
        return "this run had written nothing" + (kept.empty() ? std::string() : ", and " + kept);
    }
    std::filesystem::path checkpoint = directory / kCheckpointFileName;
    std::error_code error;
    if (!std::filesystem::exists(checkpoint, error)) return "no checkpoint had been written yet";
    return checkpoint.string() + " is intact: run the same command with --resume " + directory.string();
}

// A lost device or a signal stops the run like any error; what it leaves to resume from
// is worth saying. Any other error of an --overwrite run that had written nothing says
// that the old run is left whole.
int withResumeHint(const OptimizeCommandOptions& options, const std::function<int()>& run) {
    try {
        return run();
    } catch (const DeviceLostError& error) {
        throw Error(std::string(error.what()) + "; " + resumeHint(options));
    } catch (const Interrupted& interrupted) {
        throw Interrupted(interrupted.signal(), std::string(interrupted.what()) + "; " + resumeHint(options));
    } catch (const Error& error) {
        const std::string kept = options.overwrite && !*options.oldRunRemoved ? oldRunKept(options) : std::string();
        if (kept.empty()) throw;
        throw Error(std::string(error.what()) + "; " + kept);
    }
}

// An epsilon given for SGD, which has none, would be dropped without a word.
void requireAdamForEpsilon(OptimizerKind optimizer) {
    if (optimizer != OptimizerKind::Adam) throw Error("--adam-epsilon: only Adam has an epsilon; the optimizer is sgd");
}

int runOptimizeScene(OptimizeCommandOptions& options, bool adamEpsilonGiven) {
    if (options.scene.file.empty()) throw Error("optimize: give a SCENE (or --experiment FILE)");
    if (options.targets.empty()) throw Error("optimize: give at least one --target");
    if (options.parameters.empty()) throw Error("optimize: give at least one --param");
    options.optimize.parameters = options.parameters;
    options.optimize.optimizer = parseOptimizerKind(options.optimizer);
    if (adamEpsilonGiven) requireAdamForEpsilon(options.optimize.optimizer);
    LossKind loss = parseLossKind(options.loss);

    LoadedScene loaded = loadSceneWithOverrides(options.scene);
    Scene& scene = loaded.scene;
    // Which part of a --target is its file depends on the scene's camera names.
    std::vector<TargetFile> targetFiles;
    std::vector<NamedOutput> inputs = filesTheSceneReads(loaded);
    for (const std::string& target : options.targets) {
        targetFiles.push_back(parseTargetArgument(target, scene));
        // A target without a camera is the first camera's: one spelling in the run's
        // identity, so that --resume accepts either.
        if (targetFiles.back().camera == scene.cameras.front().name) targetFiles.back().camera.clear();
        inputs.push_back({"--target", targetFiles.back().file});
    }
    requireRunWritesNoInput(options.out, false, inputs);
    requireOptimisableParameters(scene, options.optimize.parameters);
    gridPriorWeights(options.optimize.parameters, gridPriorWeightsOf(options.optimize));
    if (options.optimize.gridLevels > 1) {
        requireADensityGridAmong(options.optimize.parameters, "coarse-to-fine grid levels are");
    }
    LogSpace(ParameterVector(scene, options.optimize.parameters), options.optimize.logParameters);
    std::vector<TargetView> views = readTargets(options.targets, scene);
    OptimizationJob job{options.scene.file, options.out, options.optimize, loss, views};
    job.inputs = {{},
                  targetFiles,
                  options.scene.assignments,
                  options.settings.spp,
                  options.settings.maxDepth,
                  options.settings.equiangularSampling};
    job.resume = !options.resume.empty();
    job.replaceOldRun = oldRunRemover(options, false);
    job.identity = requireRunCanStart(job, scene);

    throwIfInterrupted();
    VulkanContext context(ContextOptions{options.device});
    std::fprintf(stderr, "%s: %zu triangles, %zu views, %u spp, max depth %u, %u iterations of %s on %s\n",
                 options.scene.file.c_str(), scene.triangles.size(), views.size(), options.settings.spp,
                 options.settings.maxDepth, options.optimize.iterations, options.optimizer.c_str(),
                 context.description().name.c_str());
    job.description = {options.commandLine, context.description().name};
    RenderedLossGradient lossGradient(context, scene, std::move(views), options.optimize.parameters,
                                      options.settings, loss);
    ProgressBar bar("optimize");
    IterationProgress progress(bar, options.optimize.iterations, job.resume);
    lossGradient.reportProgress(progress.withinIteration());
    OptimizationReport report = runOptimization(lossGradient, scene, job, progress.onIteration());
    bar.finish();
    requireNoValidationMessages(context);
    printOutputs(options.out, report, false);
    return 0;
}

void applyOverrides(const OptimizeCommandOptions& options, const ExperimentOverrides& given, Experiment& experiment) {
    if (given.iterations->count()) experiment.optimize.iterations = options.optimize.iterations;
    if (given.learningRate->count()) experiment.optimize.learningRate = options.optimize.learningRate;
    if (given.learningRateDecay->count()) {
        experiment.optimize.learningRateDecay = options.optimize.learningRateDecay;
    }
    if (given.learningRateDecayStart->count()) {
        experiment.optimize.learningRateDecayStart = options.optimize.learningRateDecayStart;
    }
    if (given.logParameters->count()) {
        experiment.optimize.logParameters = options.optimize.logParameters;
        experiment.givenOnCommandLine["log_parameters"] = "--log-param";
    }
    if (given.adamEpsilon->count()) experiment.optimize.adamEpsilon = options.optimize.adamEpsilon;
    if (given.optimizer->count()) experiment.optimize.optimizer = parseOptimizerKind(options.optimizer);
    if (given.adamEpsilon->count()) requireAdamForEpsilon(experiment.optimize.optimizer);
    if (given.optimizer->count() && experiment.optimize.optimizer != OptimizerKind::Adam &&
        experiment.adamEpsilonInFile) {
        throw Error(experiment.file.string() + ": adam_epsilon: only Adam has an epsilon, and --optimizer sgd is "
                    "given");
    }
    if (given.smoothness->count()) {
        experiment.optimize.smoothness = options.optimize.smoothness;
        experiment.givenOnCommandLine["smoothness"] = "--smoothness";
    }
    if (given.sparsity->count()) {
        experiment.optimize.sparsity = options.optimize.sparsity;
        experiment.givenOnCommandLine["sparsity"] = "--sparsity";
    }
    if (given.totalVariation->count()) {
        experiment.optimize.totalVariation = options.optimize.totalVariation;
        experiment.givenOnCommandLine["total_variation"] = "--total-variation";
    }
    if (given.gridLevels->count()) {
        experiment.optimize.gridLevels = options.optimize.gridLevels;
        experiment.givenOnCommandLine["grid_levels"] = "--grid-levels";
    }
    if (given.seed->count()) experiment.optimize.seed = options.settings.seed;
    if (given.spp->count()) experiment.render.spp = options.settings.spp;
    if (given.maxDepth->count()) experiment.render.maxDepth = options.settings.maxDepth;
    experiment.render.equiangularSampling = options.settings.equiangularSampling;
    // How paths are split into passes changes no result, so the file does not say it.
    experiment.render.pathsPerPass = options.settings.pathsPerPass;
    if (given.loss->count()) experiment.loss = parseLossKind(options.loss);
}

// `backend` showing a bar while the renders that precede the first iteration run: each
// view's target, and each held-out view's target and true render.
ExperimentBackend withTargetProgress(ExperimentBackend backend, const Experiment& experiment) {
    const size_t total = experiment.views.size() + 2 * experiment.heldOutViews.size();
    auto bar = std::make_shared<ProgressBar>("targets");
    auto done = std::make_shared<size_t>(0);
    backend.render = [render = std::move(backend.render), bar, done, total](const Scene& scene,
                                                                            const RenderSettings& settings) {
        auto status = [&] { return std::to_string(*done) + "/" + std::to_string(total) + " renders"; };
        if (*done == 0) bar->update(0.0, status());
        Image image = render(scene, settings);
        if (*done < total) {
            ++*done;
            bar->update(double(*done) / double(total), status());
            if (*done == total) bar->finish();
        }
        return image;
    };
    return backend;
}

int runOptimizeExperiment(const OptimizeCommandOptions& options, const ExperimentOverrides& overrides) {
    if (!options.scene.file.empty() || !options.targets.empty() || !options.parameters.empty() ||
        !options.scene.assignments.empty()) {
        throw Error("--experiment: the experiment file gives the scene, targets and parameters; "
                    "drop SCENE, --target, --param and --set");
    }
    Experiment experiment = readExperiment(options.experiment);
    requireRunWritesNoInput(options.out, true, {{"the experiment's scene", experiment.scene}});
    applyOverrides(options, overrides, experiment);
    experiment.optimize.checkpointEvery = options.optimize.checkpointEvery;
    // Not requireCamera: the experiment's own cameras may be the scene's only ones
    // (startExperiment below adds them, and refuses views of a scene without one).
    LoadedScene loaded = loadScene(experiment.scene, options.scene.access);
    for (const std::string& warning : loaded.warnings) printWarning(warning);
    requireRunWritesNoInput(options.out, true, filesTheSceneReads(loaded));
    OptimizationJob job =
        startExperiment(experiment, loaded.scene, options.out, !options.resume.empty(), oldRunRemover(options, true));
    for (const std::string& warning : sceneWarnings(loaded.scene, experiment.scene)) printWarning(warning);

    throwIfInterrupted();
    VulkanContext context(ContextOptions{options.device});
    // Only parameter values change during an experiment, never the geometry.
    Bvh bvh = buildBvh(loaded.scene.positions, loaded.scene.triangles);
    ProgressBar bar("optimize");
    IterationProgress progress(bar, experiment.optimize.iterations, !options.resume.empty());
    ExperimentBackend backend =
        withTargetProgress(renderingBackend(context, bvh, progress.withinIteration()), experiment);
    std::fprintf(stderr, "%s: %s, %zu triangles, %zu views, %u spp (targets %u), %u iterations of %s on %s\n",
                 options.experiment.c_str(), experiment.scene.string().c_str(), loaded.scene.triangles.size(),
                 experiment.views.size(), experiment.render.spp, experiment.targetSpp,
                 experiment.optimize.iterations, optimizerKindName(experiment.optimize.optimizer).c_str(),
                 context.description().name.c_str());

    job.description = {options.commandLine, context.description().name};
    OptimizationReport report =
        runExperiment(experiment, loaded.scene, backend, std::move(job), progress.onIteration());
    bar.finish();
    requireNoValidationMessages(context);
    printOutputs(options.out, report, true);
    return 0;
}

}  // namespace

CommandAction addOptimizeCommand(CLI::App& app, std::string commandLine) {
    CLI::App* command = app.add_subcommand(
        "optimize", "Fit scene parameters to target images by gradient descent (or run an --experiment file)");
    auto options = std::make_shared<OptimizeCommandOptions>();
    options->commandLine = std::move(commandLine);
    addSceneOptions(*command, options->scene);
    command->get_option("scene")->required(false);
    command->add_option("--target", options->targets,
                        "Target image (EXR, PNG or JPEG) of the first camera, or CAMERA=FILE (repeatable, one per "
                        "view); each view renders at its target's size")
        ->check(nonEmpty("an image file"));
    command->add_option("--param", options->parameters, "Parameter to optimise, e.g. media/fog/sigma_a (repeatable)");
    command->add_option("--experiment", options->experiment,
                        "Run a self-contained experiment file (see " +
                            docReference("Optimisation guide", "optimisation.md") + ") instead of SCENE")
        ->check(nonEmpty("a file name"));
    ExperimentOverrides overrides;
    overrides.iterations = command->add_option("--iters", options->optimize.iterations, "Iterations")
                               ->default_val(options->optimize.iterations)->transform(integerIn(1, 1000000));
    overrides.learningRate = command->add_option("--lr", options->optimize.learningRate, "Learning rate")
                                 ->default_val(options->optimize.learningRate)->check(finitePositiveNumber());
    overrides.learningRateDecay =
        command->add_option("--lr-decay", options->optimize.learningRateDecay,
                            "The learning rate at the last iteration as a fraction of --lr (exponential decay)")
            ->default_val(options->optimize.learningRateDecay)
            ->check(finiteNumberIn(OptimizeOptions::kLeastLearningRateDecay, 1.0));
    overrides.learningRateDecayStart =
        command->add_option("--lr-decay-start", options->optimize.learningRateDecayStart,
                            "The fraction of the iterations run at the full rate before the decay starts")
            ->default_val(options->optimize.learningRateDecayStart)
            ->check(finiteNumberIn(0.0, OptimizeOptions::kMostLearningRateDecayStart));
    overrides.logParameters =
        command->add_option("--log-param", options->optimize.logParameters,
                            "Optimise this parameter (one of the --param, positive) as the logarithm of its value: "
                            "steps are relative changes and --lr is in log units (repeatable)");
    overrides.adamEpsilon =
        command->add_option("--adam-epsilon", options->optimize.adamEpsilon,
                            "Adam's epsilon, in the gradient's units: make it smaller than the gradients (Adam only)")
            ->default_val(options->optimize.adamEpsilon)->check(finitePositiveNumber());
    overrides.smoothness =
        command->add_option("--smoothness", options->optimize.smoothness,
                            "Add this weight times the mean squared difference between face-neighbouring voxels of "
                            "every grid optimised (density or emission grid) to the loss (0: none)")
            ->default_val(options->optimize.smoothness)->check(finiteNumberIn(0.0, kMostGridPriorWeight));
    overrides.sparsity =
        command->add_option("--sparsity", options->optimize.sparsity,
                            "Add this weight times the mean value of every grid optimised (density or emission grid) to the "
                            "loss, emptying what the images do not ask to fill (0: none)")
            ->default_val(options->optimize.sparsity)->check(finiteNumberIn(0.0, kMostGridPriorWeight));
    overrides.totalVariation =
        command->add_option("--total-variation", options->optimize.totalVariation,
                            "Add this weight times the mean absolute difference between face-neighbouring voxels of "
                            "every grid optimised (density or emission grid) to the loss: smooths like --smoothness but "
                            "keeps edges sharp (0: none)")
            ->default_val(options->optimize.totalVariation)->check(finiteNumberIn(0.0, kMostGridPriorWeight));
    overrides.gridLevels =
        command
            ->add_option("--grid-levels", options->optimize.gridLevels,
                         "Fit grids (density or emission) coarse to fine in N equal parts of the run: the first restricts the steps "
                         "to a grid 2^(N-1) times coarser, each next halves that (1: the grid's own voxels)")
            ->default_val(options->optimize.gridLevels)
            ->transform(integerIn(1, kMostGridLevels));
    overrides.optimizer = command->add_option("--optimizer", options->optimizer, "adam or sgd")
                              ->default_val(options->optimizer)->check(CLI::IsMember({"adam", "sgd"}));
    SamplingOptions sampling = addSamplingOptions(*command, options->settings);
    overrides.spp = sampling.spp->description("Samples per pixel per iteration");
    overrides.maxDepth = sampling.maxDepth;
    overrides.seed = sampling.seed->description("Base seed: iteration i renders with seed + i");
    overrides.loss = command->add_option("--loss", options->loss, "l2 or l1 (means over pixels and channels)")
                         ->default_val(options->loss)->check(CLI::IsMember({"l2", "l1"}));
    CLI::Option* out =
        command
            ->add_option("--out", options->out,
                         "Output directory, created if missing; one that holds another run's files (log.jsonl, "
                         "checkpoint.json, params.json, ...) is refused unless --overwrite")
            ->default_val(options->out);
    command->add_flag("--overwrite", options->overwrite,
                      "Replace the run that --out holds: its files (checkpoint included) are removed just "
                      "before the new run writes its first (the log, after iteration 0), so a run that fails "
                      "or is stopped before then leaves the old one whole; other files are left");
    command
        ->add_option("--checkpoint-every", options->optimize.checkpointEvery,
                     "Write DIR/checkpoint.json every K iterations (0: only when SIGINT or SIGTERM stops the run); "
                     "a run that fails otherwise loses at most K")
        ->default_val(options->optimize.checkpointEvery)
        ->transform(integerIn(0, 1000000));
    command->add_option("--resume", options->resume,
                        "Continue the stopped run whose --out was DIR, from DIR/checkpoint.json; give the same "
                        "scene, targets, parameters and options. SIGINT or SIGTERM stops a run with a checkpoint of "
                        "its last finished iteration and exit code 130 (SIGINT) or 143 (SIGTERM)")
        ->check(nonEmpty("a directory"));
    command->add_option("--device", options->device, "Vulkan device index or part of its name (see `info`; default: the best available)")
        ->check(nonEmpty("an index or part of a name"));
    return [command, options, overrides, out]() {
        if (!command->parsed()) return -1;
        options->optimize.seed = options->settings.seed;
        applyResume(*options, out);
        requireRunDirectory(*options);
        return withResumeHint(*options, [&] {
            return options->experiment.empty() ? runOptimizeScene(*options, overrides.adamEpsilon->count() > 0)
                                               : runOptimizeExperiment(*options, overrides);
        });
    };
}

}  // namespace vkdr
