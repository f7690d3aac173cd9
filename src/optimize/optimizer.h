#pragma once
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkdr {

enum class OptimizerKind { Adam, Sgd };

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
    // Multiplies every learning rate in the following steps (a schedule's current factor).
    void setLearningRateScale(double scale) { learningRateScale_ = scale; }

protected:
    double learningRateScale_ = 1.0;
};

// One learning rate per value (a parameter's rate repeated for each of its values).
// Throws vkdr::Error for a rate that is not > 0.
std::unique_ptr<Optimizer> makeOptimizer(OptimizerKind kind, std::vector<double> learningRates);

}  // namespace vkdr
