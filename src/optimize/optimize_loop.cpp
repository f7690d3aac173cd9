#include "optimize/optimize_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "diff/unrepresentable_render.h"
#include "optimize/coarse_grid_gradient.h"
#include "optimize/density_grid_options.h"
#include "optimize/log_space.h"
#include "optimize/parameter_vector.h"
#include "optimize/scene_emission_bound.h"
#include "scene/parameters.h"
#include "scene/scene_medium_emission.h"

namespace vkdr {
namespace {

std::vector<double> perValueLearningRates(const ParameterVector& parameters, const OptimizeOptions& options) {
    for (const auto& [name, rate] : options.learningRates) {
        if (std::find(parameters.names().begin(), parameters.names().end(), name) == parameters.names().end()) {
            throw Error("a learning rate is given for '" + name + "', which is not being optimised");
        }
    }
    std::vector<double> rates;
    for (size_t i = 0; i < parameters.names().size(); ++i) {
        auto found = options.learningRates.find(parameters.names()[i]);
        rates.insert(rates.end(), parameters.count(i),
                     found == options.learningRates.end() ? options.learningRate : found->second);
    }
    return rates;
}

std::string numberText(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value);
    return text;
}

std::string valuesText(std::span<const double> values) {
    std::string text;
    for (double value : values) text += (text.empty() ? "" : ", ") + numberText(value);
    return "[" + text + "]";
}

// Beyond this magnitude a value is far outside any scene's scale, and the renderer's
// float arithmetic (an optical depth, a squared difference) may overflow on it.
constexpr double kExtremeMagnitude = 1e6;

// The radiance that every ray leaving the scene gathers from an emitting scene-wide
// medium, emission / (sigma_a + sigma_s), where it is extreme in a channel (its sigmas
// stepped to 0, or to the least that keepSceneWideEmissionBounded allows): that, named.
std::optional<std::string> extremeSceneWideEmission(const Scene& scene) {
    const Medium* medium = boundedSceneWideMedium(scene);
    if (!medium) return std::nullopt;
    for (int c = 0; c < 3; ++c) {
        const EmissionAndAttenuation values = emissionAndAttenuation(*medium, c);
        const double radiance = values.emission / (values.sigma_a + values.sigma_s);
        if (values.emission > 0.0 && !(radiance <= kExtremeMagnitude)) {
            return "every ray that leaves the scene gathers emission / (sigma_a + sigma_s) = " + numberText(radiance) +
                   " (channel " + "RGB"[c] + ") from the scene-wide medium '" + medium->name + "', beyond " +
                   numberText(kExtremeMagnitude) +
                   ": the render's float arithmetic overflows there (a smaller learning rate keeps its sigmas from "
                   "0)";
        }
    }
    return std::nullopt;
}

// Why a loss or gradient the render gave is not finite. Targets, parameters and
// checkpoints are refused at load when they are not finite, and a step that leaves
// float range is caught by requireFiniteSteps, so it is a render beyond float range
// (values, fitted or not, that each lie in their range but together make too much
// light), an emitting scene-wide medium whose sigmas the steps took to (nearly) 0, an
// extreme value the steps reached, or the renderer itself.
std::string nonFiniteCause(const GradientResult& result, const ParameterVector& parameters, const Scene& scene) {
    if (std::optional<std::string> bad = unrepresentableRender(result)) {
        return *bad + ": the scene's values, fitted or not, make more light than a float holds";
    }
    if (std::optional<std::string> emission = extremeSceneWideEmission(scene)) return *emission;
    std::string extreme;
    for (size_t i = 0; i < parameters.names().size(); ++i) {
        std::span<const double> values = parameters.values().subspan(parameters.offset(i), parameters.count(i));
        bool isExtreme = std::any_of(values.begin(), values.end(),
                                     [](double value) { return std::abs(value) > kExtremeMagnitude; });
        if (isExtreme) extreme += (extreme.empty() ? "" : ", ") + parameters.names()[i] + " = " + valuesText(values);
    }
    if (!extreme.empty()) {
        return "extreme values (beyond " + numberText(kExtremeMagnitude) + " in magnitude): " + extreme +
               "; the render's float arithmetic overflows there";
    }
    return "no value is extreme, so the render itself produced it: please report it with the scene and command";
}

// Whether `holds` is true of every value, checked in parallel: a grid's millions of
// voxels are checked in every iteration.
template <typename Predicate>
bool allValues(std::span<const double> values, Predicate holds) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, values.size()), true,
        [&](const tbb::blocked_range<size_t>& range, bool all) {
            return all && std::all_of(values.begin() + long(range.begin()), values.begin() + long(range.end()), holds);
        },
        std::logical_and<bool>());
}

void requireFinite(const GradientResult& result, const ParameterVector& parameters, const Scene& scene,
                   uint32_t iteration) {
    std::string where = "iteration " + std::to_string(iteration) + ": ";
    const std::string kept = "; no values from this iteration were kept; ";
    if (!std::isfinite(result.loss)) {
        std::string at;
        for (size_t i = 0; i < parameters.names().size(); ++i) {
            at += (at.empty() ? "" : ", ") + parameters.names()[i] + " = " +
                  valuesText(parameters.values().subspan(parameters.offset(i), parameters.count(i)));
        }
        throw Error(where + "the loss is " + numberText(result.loss) + " at " + at + kept +
                    nonFiniteCause(result, parameters, scene));
    }
    for (size_t i = 0; i < result.parameters.size(); ++i) {
        const ParameterGradient& parameter = result.parameters[i];
        if (allValues(parameter.gradient, [](double gradient) { return std::isfinite(gradient); })) continue;
        for (double gradient : parameter.gradient) {
            if (!std::isfinite(gradient)) {
                std::span<const double> values =
                    parameters.values().subspan(parameters.offset(i), parameters.count(i));
                throw Error(where + "the gradient of " + parameter.name + " is " + numberText(gradient) + " at " +
                            parameter.name + " = " + valuesText(values) + kept + nonFiniteCause(result, parameters, scene));
            }
        }
    }
}

// A finite gradient can still step a value past what a float holds (SGD with a large
// rate); the scene stores floats, so such a step must not reach it, upwards or
// downwards, whatever bound it would be clamped to.
void requireFiniteSteps(const ParameterVector& parameters, uint32_t iteration) {
    if (allValues(parameters.values(), [](double value) { return std::isfinite(float(value)); })) return;
    for (size_t i = 0; i < parameters.names().size(); ++i) {
        for (size_t c = 0; c < parameters.count(i); ++c) {
            double value = parameters.values()[parameters.offset(i) + c];
            if (!std::isfinite(float(value))) {
                throw Error("iteration " + std::to_string(iteration) + ": the step took " + parameters.names()[i] +
                            " to " + numberText(value) +
                            ", beyond float range; no values from this iteration were kept (try a smaller "
                            "learning rate)");
            }
        }
    }
}

// An evaluation whose values do not render (a step that left a grid too dense to track)
// names its iteration. Other failures (a lost device) keep their kind.
GradientResult evaluateAt(LossGradient& lossGradient, const Scene& scene, uint32_t seed, uint32_t iteration) {
    try {
        return lossGradient.evaluate(scene, seed);
    } catch (const UnrenderableValuesError& failure) {
        throw Error("iteration " + std::to_string(iteration) + ": " + failure.what());
    }
}

// No evaluation renders the values the last step leaves, which the run writes out as
// its fit: they are rendered once more, so that a run does not end with a fit that does
// not render. A signal during that render stops only the check: the iterations are done,
// and a signal after them lets the outputs be written (optimization_run.cpp).
void requireLastStepRenders(LossGradient& lossGradient, const Scene& scene, const OptimizeOptions& options) {
    try {
        lossGradient.requireRenderable(scene, options.seed + options.iterations);
    } catch (const Interrupted&) {
    } catch (const UnrenderableValuesError& failure) {
        throw Error("the values of the last step (iteration " + std::to_string(options.iterations - 1) +
                    ") do not render: " + failure.what() + "; a smaller learning rate takes smaller steps");
    }
}

// The gradient in the ParameterVector's layout, not yet checked to be finite. A LossGradient that does not answer for
// exactly the parameters asked for is a bug, not a user error.
std::vector<double> flatGradient(const ParameterVector& parameters, const GradientResult& result) {
    if (result.parameters.size() != parameters.names().size()) {
        throw std::logic_error("LossGradient returned " + std::to_string(result.parameters.size()) +
                               " parameters, expected " + std::to_string(parameters.names().size()));
    }
    std::vector<double> gradient;
    for (size_t i = 0; i < result.parameters.size(); ++i) {
        const ParameterGradient& parameter = result.parameters[i];
        if (parameter.name != parameters.names()[i] || parameter.gradient.size() != parameters.count(i)) {
            throw std::logic_error("LossGradient returned '" + parameter.name + "' with " +
                                   std::to_string(parameter.gradient.size()) + " values where '" +
                                   parameters.names()[i] + "' was expected");
        }
        gradient.insert(gradient.end(), parameter.gradient.begin(), parameter.gradient.end());
    }
    return gradient;
}

// Each density grid's slice of the ParameterVector: what coarse-to-fine levels filter.
struct GridSlice {
    size_t offset = 0;
    size_t count = 0;
    glm::ivec3 size{0};
};

std::vector<GridSlice> densityGridSlices(const Scene& scene, const ParameterVector& parameters) {
    std::vector<GridSlice> slices;
    for (size_t i = 0; i < parameters.names().size(); ++i) {
        // Coarse-to-fine fitting works on grids of one value per voxel.
        const DensityGrid* grid = densityGridOf(scene, parameters.names()[i]);
        if (grid && grid->channels == 1) {
            slices.push_back({parameters.offset(i), parameters.count(i), grid->size});
        }
    }
    return slices;
}

void coarsenGridGradients(const std::vector<GridSlice>& slices, uint32_t divisor, std::span<double> gradient) {
    for (const GridSlice& slice : slices) {
        coarsenGridGradient(slice.size, divisor, gradient.subspan(slice.offset, slice.count));
    }
}

// The exponent of the learning rate decay: 0 until the decay starts, 1 at the last iteration.
double decayProgress(const OptimizeOptions& options, uint32_t iteration) {
    if (options.iterations < 2) {
        return 0.0;
    }
    double run = double(iteration) / double(options.iterations - 1);
    return std::max(0.0, (run - options.learningRateDecayStart) / (1.0 - options.learningRateDecayStart));
}

void restore(const LoopState& state, const OptimizeOptions& options, ParameterVector& parameters,
             Optimizer& optimizer, OptimizeResult& result) {
    if (state.iteration >= options.iterations || state.losses.size() != state.iteration) {
        throw Error("cannot resume after iteration " + std::to_string(state.iteration) + " with " +
                    std::to_string(state.losses.size()) + " losses in a run of " +
                    std::to_string(options.iterations) + " iterations");
    }
    if (state.values.size() != parameters.size()) {
        throw Error("cannot resume with " + std::to_string(state.values.size()) + " values where " +
                    std::to_string(parameters.size()) + " are optimised");
    }
    optimizer.restore(state.optimizer);
    std::copy(state.values.begin(), state.values.end(), parameters.values().begin());
    result.losses = state.losses;
    result.forwardMs = state.forwardMs;
    result.adjointMs = state.adjointMs;
}

}  // namespace

OptimizeResult optimize(LossGradient& lossGradient, Scene& scene, const OptimizeOptions& options,
                        const OptimizeCallbacks& callbacks, const LoopState* resume) {
    if (options.iterations == 0) {
        throw Error("the number of iterations must be at least 1");
    }
    if (!(options.learningRateDecay > 0.0 && options.learningRateDecay <= 1.0)) {
        throw Error("the learning rate decay must be in (0, 1], got " + std::to_string(options.learningRateDecay));
    }
    if (!(options.learningRateDecayStart >= 0.0 && options.learningRateDecayStart < 1.0)) {
        throw Error("the learning rate decay start must be in [0, 1), got " +
                    std::to_string(options.learningRateDecayStart));
    }
    ParameterVector parameters(scene, options.parameters);
    std::unique_ptr<Optimizer> optimizer = makeOptimizer(options.optimizer, perValueLearningRates(parameters, options), options.adamEpsilon);
    OptimizeResult result;
    uint32_t first = 0;
    if (resume) {
        restore(*resume, options, parameters, *optimizer, result);
        parameters.writeTo(scene);
        first = resume->iteration;
    }
    const LogSpace logSpace(parameters, options.logParameters);
    const std::vector<GridSlice> gridSlices = densityGridSlices(scene, parameters);
    if (options.gridLevels > 1) {
        requireADensityGridAmong(options.parameters, "coarse-to-fine grid levels are");
    }
    auto stateAfter = [&](uint32_t done) {
        std::vector<double> values(parameters.values().begin(), parameters.values().end());
        return LoopState{done, std::move(values), optimizer->state(), result.losses, result.forwardMs,
                         result.adjointMs};
    };
    for (uint32_t iteration = first; iteration < options.iterations; ++iteration) {
        const auto started = std::chrono::steady_clock::now();
        GradientResult evaluation;
        std::vector<Metric> metrics;
        try {
            throwIfInterrupted();
            evaluation = evaluateAt(lossGradient, scene, options.seed + iteration, iteration);
            requireFinite(evaluation, parameters, scene, iteration);
            if (callbacks.measure) metrics = callbacks.measure(scene, iteration);
        } catch (const Interrupted&) {
            // Stopped between iterations or within one (its evaluation or the renders
            // that measure it): what the finished ones reached is worth keeping,
            // whenever the last checkpoint was.
            if (callbacks.checkpoint && iteration > first) callbacks.checkpoint(stateAfter(iteration));
            throw;
        }
        std::vector<double> gradient = flatGradient(parameters, evaluation);

        coarsenGridGradients(gridSlices, gridDivisorAt(iteration, options.iterations, options.gridLevels), gradient);
        optimizer->setLearningRateScale(std::pow(options.learningRateDecay, decayProgress(options, iteration)));
        logSpace.enter(parameters.values(), gradient);
        optimizer->step(parameters.values(), gradient);
        logSpace.leave(parameters.values());
        requireFiniteSteps(parameters, iteration);  // before the bounds clamp a step beyond float range
        parameters.project();
        keepSceneWideEmissionBounded(parameters, scene);
        parameters.writeTo(scene);
        const double iterationMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();

        result.losses.push_back(evaluation.loss);
        result.iterationMs += iterationMs;
        ++result.iterationsRun;
        result.forwardMs += evaluation.forwardMs;
        result.adjointMs += evaluation.adjointMs;
        result.truncatedPaths += evaluation.truncatedPaths;
        result.lastMetrics = metrics;
        if (callbacks.iterationDone) {
            callbacks.iterationDone(IterationRecord{iteration, evaluation.loss, std::move(evaluation.parameters),
                                                    std::move(metrics), evaluation.forwardMs, evaluation.adjointMs,
                                                    iterationMs});
        }
        if (iteration == 0) result.firstImages = evaluation.images;
        result.lastImages = std::move(evaluation.images);
        uint32_t done = iteration + 1;
        if (callbacks.checkpoint && options.checkpointEvery > 0 && done % options.checkpointEvery == 0 &&
            done < options.iterations) {
            callbacks.checkpoint(stateAfter(done));
        }
    }
    requireLastStepRenders(lossGradient, scene, options);
    return result;
}

}  // namespace vkdr
