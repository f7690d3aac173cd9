#pragma once
#include <vector>

#include "optimize/optimizer.h"

namespace vkdr {

// Plain gradient descent: value -= learningRate * gradient. The step scales with the
// gradient, so the learning rate must suit the loss's scale (Adam's does not).
class SgdOptimizer : public Optimizer {
public:
    explicit SgdOptimizer(std::vector<double> learningRates) : learningRates_(std::move(learningRates)) {}
    void step(std::span<double> values, std::span<const double> gradients) override;

private:
    std::vector<double> learningRates_;
};

}  // namespace vkdr
