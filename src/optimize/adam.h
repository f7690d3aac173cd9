#pragma once
#include <cstdint>
#include <vector>

#include "optimize/optimizer.h"

namespace vkdr {

struct AdamMoments {
    double beta1 = 0.9;     // decay of the running mean of gradients
    double beta2 = 0.999;   // decay of the running mean of squared gradients
    // Keeps the step finite where gradients vanish. It is in the gradient's units: a
    // gradient far below it gets a step far below the rate.
    double epsilon = 1e-8;
};

// Adam (Kingma and Ba 2015) with bias-corrected moments: each value moves by about its
// learning rate per step whatever its gradient's scale, which suits parameters whose
// gradients differ by orders of magnitude (sigma of thin fog against a base colour).
class AdamOptimizer : public Optimizer {
public:
    explicit AdamOptimizer(std::vector<double> learningRates, const AdamMoments& moments = {});
    void step(std::span<double> values, std::span<const double> gradients) override;
    OptimizerState state() const override { return {steps_, mean_, meanSquare_}; }
    void restore(const OptimizerState& state) override;

private:
    std::vector<double> learningRates_;
    AdamMoments moments_;
    std::vector<double> mean_;        // m: running mean of the gradient
    std::vector<double> meanSquare_;  // v: running mean of the squared gradient
    uint64_t steps_ = 0;              // t: steps taken, for the bias correction
};

}  // namespace vkdr
