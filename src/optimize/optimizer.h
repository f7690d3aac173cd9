#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkdr {

enum class OptimizerKind { Adam, Sgd };

// Everything an optimiser carries from one step to the next, so that a run restored
// from a checkpoint takes exactly the steps the uninterrupted run would have taken.
struct OptimizerState {
    uint64_t steps = 0;              // steps taken
    std::vector<double> mean;        // Adam's m, one per value (empty for SGD)
    std::vector<double> meanSquare;  // Adam's v, one per value (empty for SGD)
};

// "adam" or "sgd"; anything else is a vkdr::Error listing both.
OptimizerKind parseOptimizerKind(std::string_view text);
std::string optimizerKindName(OptimizerKind kind);

// A first-order optimiser over a flat vector of parameter values, keeping one state per
// value. Constraints are not its business: the caller projects after each step.
class Optimizer {
public:
    virtual ~Optimizer() = default;
    // Moves `values` against `gradients` (dLoss/dvalue, same length as at construction).
    virtual void step(std::span<double> values, std::span<const double> gradients) = 0;
    virtual OptimizerState state() const = 0;
    // Continues from a state() of an optimiser of the same kind over as many values.
    // Throws vkdr::Error when the state does not fit.
    virtual void restore(const OptimizerState& state) = 0;
    // Multiplies every learning rate in the following steps (a schedule's current factor).
    void setLearningRateScale(double scale) { learningRateScale_ = scale; }

protected:
    double learningRateScale_ = 1.0;
};

// One learning rate per value (a parameter's rate repeated for each of its values), and
// Adam's epsilon (adam.h). Throws vkdr::Error for a rate or an epsilon that is not > 0.
std::unique_ptr<Optimizer> makeOptimizer(OptimizerKind kind, std::vector<double> learningRates,
                                         double adamEpsilon);

}  // namespace vkdr
