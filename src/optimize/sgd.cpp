#include "optimize/sgd.h"

#include <cassert>

namespace vkdr {

void SgdOptimizer::step(std::span<double> values, std::span<const double> gradients) {
    assert(values.size() == learningRates_.size() && gradients.size() == learningRates_.size());
    for (size_t i = 0; i < values.size(); ++i) {
        values[i] -= learningRateScale_ * learningRates_[i] * gradients[i];
    }
}

}  // namespace vkdr
