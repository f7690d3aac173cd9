#include "optimize/adam.h"

#include <cassert>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace vkdr {

AdamOptimizer::AdamOptimizer(std::vector<double> learningRates, const AdamMoments& moments)
    : learningRates_(std::move(learningRates)),
      moments_(moments),
      mean_(learningRates_.size(), 0.0),
      meanSquare_(learningRates_.size(), 0.0) {}

void AdamOptimizer::step(std::span<double> values, std::span<const double> gradients) {
    assert(values.size() == mean_.size() && gradients.size() == mean_.size());
    ++steps_;
    // m and v start at 0, so early averages are biased towards 0 by (1 - beta^t).
    double meanCorrection = 1.0 - std::pow(moments_.beta1, double(steps_));
    double meanSquareCorrection = 1.0 - std::pow(moments_.beta2, double(steps_));
    // Each value on its own: a grid's millions of voxels step in parallel, with the same bits.
    tbb::parallel_for(size_t(0), values.size(), [&](size_t i) {
        mean_[i] = moments_.beta1 * mean_[i] + (1.0 - moments_.beta1) * gradients[i];
        meanSquare_[i] = moments_.beta2 * meanSquare_[i] + (1.0 - moments_.beta2) * gradients[i] * gradients[i];
        const double meanHat = mean_[i] / meanCorrection;
        const double meanSquareHat = meanSquare_[i] / meanSquareCorrection;
        values[i] -= learningRateScale_ * learningRates_[i] * meanHat / (std::sqrt(meanSquareHat) + moments_.epsilon);
    });
}

void AdamOptimizer::restore(const OptimizerState& state) {
    if (state.mean.size() != mean_.size() || state.meanSquare.size() != meanSquare_.size()) {
        throw Error("the Adam state holds " + std::to_string(state.mean.size()) + " and " +
                    std::to_string(state.meanSquare.size()) + " moments where " + std::to_string(mean_.size()) +
                    " values are optimised");
    }
    steps_ = state.steps;
    mean_ = state.mean;
    meanSquare_ = state.meanSquare;
}

}  // namespace vkdr
