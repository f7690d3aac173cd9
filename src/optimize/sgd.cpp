#include "optimize/sgd.h"

#include <cassert>

#include "core/error.h"

namespace vkdr {

void SgdOptimizer::step(std::span<double> values, std::span<const double> gradients) {
    assert(values.size() == learningRates_.size() && gradients.size() == learningRates_.size());
    ++steps_;
    for (size_t i = 0; i < values.size(); ++i) {
        values[i] -= learningRateScale_ * learningRates_[i] * gradients[i];
    }
}

void SgdOptimizer::restore(const OptimizerState& state) {
    if (!state.mean.empty() || !state.meanSquare.empty()) {
        throw Error("the state holds moments, which SGD does not keep: it was written by Adam");
    }
    steps_ = state.steps;
}

}  // namespace vkdr
