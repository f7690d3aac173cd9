#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "image/image.h"
#include "optimize/optimizer.h"
#include "scene/scene.h"

namespace vkdr {

struct OptimizeOptions {
    std::vector<std::string> parameters;  // names as in scene/parameters.h, in this order everywhere
    OptimizerKind optimizer = OptimizerKind::Adam;
    double learningRate = 0.01;
    std::map<std::string, double> learningRates;  // per-parameter overrides of learningRate
    // Parameters stepped as log(value) (optimize/log_space.h); their rates are in log
    // units, a relative change per step.
    std::vector<std::string> logParameters;
    // Adam's epsilon (optimize/adam.h), in the units of the gradient it is added to: a
    // loss whose gradients are far smaller (a faint image) needs a smaller one.
    double adamEpsilon = 1e-8;
    // The rates at the last iteration as a fraction of the first, decaying exponentially:
    // iteration i uses rate * learningRateDecay^p, where p rises from 0 at
    // learningRateDecayStart * (iterations - 1) to 1 at the last iteration. Below 1 it damps
    // the noise-driven wandering around the minimum that a constant rate keeps up.
    double learningRateDecay = 1.0;
    static constexpr double kLeastLearningRateDecay = 1e-9;
    // The fraction of the iterations that run at the full rate before the decay starts,
    // up to kMostLearningRateDecayStart: the values can travel to the minimum first, then
    // settle on it.
    double learningRateDecayStart = 0.0;
    static constexpr double kMostLearningRateDecayStart = 0.999;
    // The weights of the priors (optimize/grid_priors.h) added to the loss for every
    // density grid optimised; 0 for none.
    double smoothness = 0.0;
    double sparsity = 0.0;
    double totalVariation = 0.0;
    // Coarse-to-fine levels for density grids (optimize/coarse_grid_gradient.h): the run
    // is split into this many equal parts, the first restricting each grid's steps to a
    // grid 2^(levels - 1) times coarser, each next part halving that; 1: the grid's own
    // voxels throughout.
    uint32_t gridLevels = 1;
    uint32_t iterations = 100;
    uint32_t seed = 0;  // iteration i renders with seed + i
    // OptimizeCallbacks::checkpoint is called after every this many iterations (0: never).
    uint32_t checkpointEvery = 10;
};

// What the loop needs to continue after `iteration` iterations exactly as if it had never
// stopped: the values after that many steps and the optimiser's state. The losses and
// times so far complete the outputs of a resumed run.
struct LoopState {
    uint32_t iteration = 0;      // iterations done; the next one to run
    std::vector<double> values;  // in ParameterVector order (optimize/parameter_vector.h)
    OptimizerState optimizer;
    std::vector<double> losses;  // one per iteration done
    double forwardMs = 0.0;      // all iterations done together
    double adjointMs = 0.0;
};

// A figure measured at an iteration's values besides the loss (an experiment's held-out
// view error, a grid's error against the true grid).
struct Metric {
    std::string name;
    double value = 0.0;
};

// One evaluation of the loop: the loss and gradient at the values before that
// iteration's step.
struct IterationRecord {
    uint32_t iteration = 0;  // counted from 0
    double loss = 0.0;
    std::vector<ParameterGradient> parameters;  // value and dLoss/dvalue, in OptimizeOptions order
    std::vector<Metric> metrics;                // from OptimizeCallbacks::measure
    double forwardMs = 0.0;
    double adjointMs = 0.0;
    // Wall clock: the evaluation, the metrics, the step and the scene's update, host work
    // included (for a large grid most of it).
    double iterationMs = 0.0;
};

struct OptimizeCallbacks {
    // Called with the scene at an iteration's values, once its loss is known and before
    // its step: what it returns goes into the iteration's record.
    std::function<std::vector<Metric>(const Scene& scene, uint32_t iteration)> measure;
    std::function<void(const IterationRecord&)> iterationDone;
    // After every OptimizeOptions::checkpointEvery iterations, except after the last one
    // (the run's outputs follow it), once `scene` holds the new values; and when a
    // signal interrupts the loop (optimize() says when).
    std::function<void(const LoopState&)> checkpoint;
};

struct OptimizeResult {
    std::vector<double> losses;     // per iteration
    std::vector<Image> lastImages;  // the last iteration's render of each view
    std::vector<Image> firstImages; // iteration 0's render of each view; empty when resumed past it
    std::vector<Metric> lastMetrics; // the last iteration's (OptimizeCallbacks::measure)
    double forwardMs = 0.0;         // all iterations together
    double adjointMs = 0.0;
    double iterationMs = 0.0;       // the iterations this call ran (not a resumed run's earlier ones), wall clock
    uint32_t iterationsRun = 0;
    uint64_t truncatedPaths = 0;    // paths cut by the segment limit in the iterations run (should be 0)
};

// Gradient descent on `scene`'s parameters: each iteration evaluates the loss and its
// gradient with seed + iteration, steps, projects onto the constraints
// (optimize/constraints.h) and writes the new values into `scene`. Throws vkdr::Error
// naming the iteration, the parameter, its values and the likely cause when the loss or
// a gradient is not finite, before anything of that iteration reaches `scene` or the
// callbacks, and an Error naming the iteration when an evaluation fails (a step that
// left a density grid too dense to track). After the last step it renders the values it
// leaves once more (LossGradient::requireRenderable, with the seed a next iteration would
// take) and throws Error if they do not render. On a SIGINT or SIGTERM
// (core/interrupt.h), noticed between iterations or within one (by the LossGradient or
// by the renders of OptimizeCallbacks::measure), it calls the checkpoint callback with
// the state after the last finished iteration (if one finished since the start or the
// resume) and rethrows Interrupted; one during the last check stops only the check.
// With `resume` (a LoopState from the checkpoint callback of a run with the same
// options) it writes resume->values into `scene` and continues from resume->iteration;
// its losses and times are part of the result.
OptimizeResult optimize(LossGradient& lossGradient, Scene& scene, const OptimizeOptions& options,
                        const OptimizeCallbacks& callbacks = {}, const LoopState* resume = nullptr);

}  // namespace vkdr
