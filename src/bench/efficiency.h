#pragma once
#include <cmath>
#include <optional>

namespace vkdr {

// Estimates of that relative noise per second: 1 / (relativeNoise^2 x seconds per
// estimate), for a render or a gradient. Where quadrupling the samples halves the noise
// and quadruples the time (independent samples), the figure does not depend on the
// samples per pixel, only on how well each sample and each second is spent; stratified
// samples, and a gradient's products of two noises, make it grow with them, so compare
// figures at equal samples per pixel. None where it is not a finite positive number: a
// noise of 0 (an image without noise) has no figure to compare, not the worst one.
inline std::optional<double> efficiencyOf(double relativeNoise, double secondsPerEstimate) {
    const double cost = relativeNoise * relativeNoise * secondsPerEstimate;
    const double efficiency = 1.0 / cost;
    return cost > 0.0 && std::isfinite(efficiency) ? std::optional(efficiency) : std::nullopt;
}

}  // namespace vkdr
