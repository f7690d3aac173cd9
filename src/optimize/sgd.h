#pragma once
#include <cstdint>
#include <vector>

#include "optimize/optimizer.h"

namespace vkdr {

// Plain gradient descent: value -= learningRate * gradient. The step scales with the
// gradient, so the learning rate must suit the loss's scale (Adam's does not).
class SgdOptimizer : public Optimizer {
public:
    explicit SgdOptimizer(std::vector<double> learningRates) : learningRates_(std::move(learningRates)) {}
    void step(std::span<double> values, std::span<const double> gradients) override;
    OptimizerState state() const override { return {steps_, {}, {}}; }
    void restore(const OptimizerState& state) override;

private:
    std::vector<double> learningRates_;
    uint64_t steps_ = 0;  // only recorded: SGD's step does not depend on it
};

}  // namespace vkdr
