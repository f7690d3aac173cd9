#pragma once
#include <string>
#include <vector>

#include "diff/rendered_loss_gradient.h"

namespace vkdr {

// One component of one parameter: the adjoint gradient against central finite
// differences of the loss with common random numbers, each the mean over several seeds
// with its standard error.
struct GradientCheckRow {
    std::string name;
    int component = 0;
    double adjoint = 0.0, adjointError = 0.0;
    double finiteDifference = 0.0, finiteDifferenceError = 0.0;
    double step = 0.0;
};

// Step per parameter: h = 1e-2 * max(|value|, 0.1) for emission, 5e-2 * max(|value|, 0.1)
// for base colour (Russian roulette follows the throughput), 1e-2 for g, and
// 0.15 * value (0.015 at 0) for sigma_a and sigma_s: a changed sigma re-routes some free
// flights (one now ends before a surface instead of after), which makes small
// steps drown in noise; the central difference's error, O((h d)^2) over optical paths
// of length d, stays below 1 % while sigma d < 1. Where value - h would leave the
// valid range (sigma = 0, base colour 0), the second-order one-sided difference
// (-3 L(x) + 4 L(x + h) - L(x + 2h)) / 2h is used instead.
double finiteDifferenceStep(const std::string& parameter, float value);

std::vector<GradientCheckRow> checkGradients(RenderedLossGradient& lossGradient, const Scene& scene,
                                             const std::vector<std::string>& parameters, int seeds);

}  // namespace vkdr
