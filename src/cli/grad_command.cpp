#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/install_layout.h"
#include "cli/number_options.h"
#include "cli/progress_bar.h"
#include "cli/sampling_options.h"
#include "cli/scene_options.h"
#include "cli/target_views.h"
#include "cli/warnings.h"
#include "core/error.h"
#include "scene/parameters.h"
#include "core/interrupt.h"
#include "diff/gradient_check.h"
#include "diff/rendered_loss_gradient.h"
#include "diff/unrepresentable_render.h"
#include "optimize/loss_kind_text.h"
#include "optimize/value_summary.h"
#include "vk/context.h"

namespace vkdr {
namespace {

struct GradOptions {
    SceneOptions scene;
    std::vector<std::string> targets;
    std::vector<std::string> parameters;
    RenderSettings settings;
    std::string loss = "l2";
    bool json = false;
    bool check = false;
    int checkSeeds = 4;
    std::string device;
};

std::vector<TargetView> readViews(const GradOptions& options, const Scene& scene) {
    std::vector<TargetView> views = readTargets(options.targets, scene);
    for (size_t i = 0; i < views.size(); ++i) {
        const std::string& target = options.targets[i];
        const Image& image = views[i].target;
        bool wrongWidth = options.settings.width > 0 && options.settings.width != image.width;
        bool wrongHeight = options.settings.height > 0 && options.settings.height != image.height;
        if (wrongWidth || wrongHeight) {
            throw Error("--target " + target + " is " + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + ", not the --width/--height asked for");
        }
    }
    return views;
}

void requireFinite(double value, const std::string& what) {
    if (!std::isfinite(value)) {
        throw Error("grad: " + what + " came out " + (std::isnan(value) ? "NaN" : "infinite") +
                    "; nothing is printed");
    }
}

// What grad prints is a number: a NaN or infinity (null in JSON) is refused, naming it.
void requireFiniteResult(const GradientResult& result, const std::vector<GradientCheckRow>& check) {
    if (std::optional<std::string> bad = unrepresentableRender(result)) {
        throw Error("grad: " + *bad + ": the scene's values make more light than a float holds; nothing is printed");
    }
    requireFinite(result.loss, "the loss");
    for (const ParameterGradient& p : result.parameters) {
        for (size_t c = 0; c < p.gradient.size(); ++c) {
            requireFinite(p.gradient[c], "d loss / d " + p.name + "[" + std::to_string(c) + "]");
        }
    }
    for (const GradientCheckRow& row : check) {
        std::string name = row.name + "[" + std::to_string(row.component) + "]";
        requireFinite(row.adjoint, "the --check adjoint of " + name);
        requireFinite(row.adjointError, "the --check adjoint's standard error of " + name);
        requireFinite(row.finiteDifference, "the --check finite difference of " + name);
        requireFinite(row.finiteDifferenceError, "the --check finite difference's standard error of " + name);
    }
}

void printGradient(const ParameterGradient& p) {
    std::printf("d loss / d %s =", p.name.c_str());
    // A gradient of many values (a texture's texels, a grid's voxels) is summarised, as
    // optimize's outputs summarise it; --json has every value.
    if (!isSummarised(p.gradient.size())) {
        for (double g : p.gradient) {
            std::printf(" %.6g", g);
        }
        std::printf("\n");
        return;
    }
    const GradientSummary summary = summariseGradient(p.gradient);
    std::printf(" %zu values, L2 norm %.6g, largest %.6g at [%zu] (--json prints them all)\n", summary.count,
                summary.l2Norm, summary.largest, summary.largestAt);
}

void printText(const GradientResult& result, const std::vector<GradientCheckRow>& check) {
    std::printf("loss %.9g\n", result.loss);
    for (const ParameterGradient& p : result.parameters) {
        printGradient(p);
    }
    if (check.empty()) {
        return;
    }
    std::printf("\n%-34s %27s %27s %10s\n", "parameter", "adjoint +- std. error", "finite diff. +- std. error",
                "step");
    bool anyUnresolved = false;
    for (const GradientCheckRow& row : check) {
        std::string name = row.name + "[" + std::to_string(row.component) + "]";
        std::printf("%-34s %13.6g +- %-10.3g ", name.c_str(), row.adjoint, row.adjointError);
        if (row.finiteDifferenceResolved) {
            std::printf("%13.6g +- %-10.3g", row.finiteDifference, row.finiteDifferenceError);
        } else {
            std::printf("%27s", "unresolved (*)");
            anyUnresolved = true;
        }
        std::printf(" %10.3g\n", row.step);
    }
    if (anyUnresolved) {
        std::printf("(*) no step changed the loss by a bit at any seed: the gradient is zero, or too small for a "
                    "finite difference to see (a value tiny against the rest of the scene)\n");
    }
}

// Keys in the order --help shows them, the gradients in the order asked for.
void printJson(const GradientResult& result, const std::vector<GradientCheckRow>& check) {
    nlohmann::ordered_json out;
    out["loss"] = result.loss;
    out["gradients"] = nlohmann::ordered_json::object();
    for (const ParameterGradient& p : result.parameters) {
        out["gradients"][p.name] = p.gradient;
    }
    if (!check.empty()) {
        out["check"] = nlohmann::ordered_json::array();
        for (const GradientCheckRow& row : check) {
            out["check"].push_back({{"parameter", row.name},
                                    {"component", row.component},
                                    {"adjoint", row.adjoint},
                                    {"adjoint_error", row.adjointError},
                                    {"finite_difference", row.finiteDifference},
                                    {"finite_difference_error", row.finiteDifferenceError},
                                    {"finite_difference_resolved", row.finiteDifferenceResolved},
                                    {"step", row.step}});
        }
    }
    std::printf("%s\n", out.dump().c_str());
}

// --check renders twice per value and seed: a texture or a grid would take hours.
constexpr size_t kMostValuesChecked = 64;

void requireCheckable(const Scene& scene, const GradOptions& options) {
    for (const std::string& name : options.parameters) {
        const size_t values = getParameter(scene, name).size();
        if (options.check && values > kMostValuesChecked) {
            throw Error("--check: " + name + " has " + std::to_string(values) + " values; finite differences of more "
                        "than " + std::to_string(kMostValuesChecked) + " would take " +
                        std::to_string(2 * values * size_t(options.checkSeeds)) + " renders");
        }
    }
    if (options.check) finiteDifferenceSteps(scene, options.parameters);
}

int runGrad(const GradOptions& options) {
    Scene scene = std::move(loadSceneWithOverrides(options.scene).scene);
    requireCheckable(scene, options);
    std::vector<TargetView> views = readViews(options, scene);
    VulkanContext context(ContextOptions{options.device});
    RenderedLossGradient lossGradient(context, scene, views, options.parameters, options.settings,
                                      parseLossKind(options.loss));
    ProgressBar bar("grad");
    bar.update(0.0, "gradient");
    // With --check the evaluation is the first of the check's steps: its adjoint
    // evaluations, seed by seed from --seed, and each value's finite differences.
    const double evaluationShare =
        options.check ? 1.0 / double(gradientCheckSteps(scene, options.parameters, options.checkSeeds)) : 1.0;
    lossGradient.reportProgress([&](double fraction) { bar.update(evaluationShare * fraction, "gradient"); });
    GradientResult result = lossGradient.evaluate(scene, options.settings.seed);
    std::vector<GradientCheckRow> check;
    if (options.check) {
        check = checkGradients(
            lossGradient, scene, options.parameters, options.checkSeeds, options.settings.seed,
            [&](double fraction) { bar.update(fraction, "--check"); }, &result);
    }
    bar.finish();
    requireNoValidationMessages(context);
    requireFiniteResult(result, check);
    throwIfInterrupted();  // a signal after the last pass: no result printed
    warnOfCutPaths(result.truncatedPaths, "the render");
    if (options.json) {
        printJson(result, check);
    } else {
        printText(result, check);
    }
    return 0;
}

}  // namespace

CommandAction addGradCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "grad", "Print the loss of a render against target images and its gradient with respect to parameters");
    auto options = std::make_shared<GradOptions>();
    addSceneOptions(*command, options->scene);
    command->add_option("--target", options->targets,
                        "Target image (EXR, PNG or JPEG); CAMERA=FILE for another camera than the first (repeatable)")
        ->required()->check(nonEmpty("an image file"));
    command->add_option("--param", options->parameters, "Parameter to differentiate, e.g. media/fog/sigma_a "
                                                        "(repeatable)")
        ->required();
    addSamplingOptions(*command, options->settings);
    command->add_option("--loss", options->loss, "l2 (mean squared difference) or l1 (mean absolute difference)")
        ->default_val(options->loss)->check(CLI::IsMember({"l2", "l1"}));
    command->add_option("--width", options->settings.width, "Must match the target's width when given")
        ->transform(integerIn(1, kMaxImageSide));
    command->add_option("--height", options->settings.height, "Must match the target's height when given")
        ->transform(integerIn(1, kMaxImageSide));
    command->add_flag("--json", options->json,
                      "Print exactly one JSON object: {\"loss\": x, \"gradients\": {...}}, with --check also "
                      "\"check\": [...], a row per value (the Gradients guide)");
    CLI::Option* checkFlag = command->add_flag("--check", options->check,
                      "Also compute central finite differences with common random numbers (the step is in " +
                          docReference("Gradients guide", "gradients.md") +
                          ") and print both with their standard errors over --check-seeds seeds from --seed on; "
                          "at most " + std::to_string(kMostValuesChecked) + " values a parameter");
    command->add_option("--check-seeds", options->checkSeeds, "Seeds the check averages over")
        ->default_val(options->checkSeeds)->transform(integerIn(2, 1000))->needs(checkFlag);
    command->add_option("--device", options->device, "Vulkan device index or part of its name (see `info`; default: the best available)")
        ->check(nonEmpty("an index or part of a name"));
    return [command, options]() { return command->parsed() ? runGrad(*options) : -1; };
}

}  // namespace vkdr
