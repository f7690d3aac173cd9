#pragma once
#include <optional>
#include <span>

namespace vkdr {

// The spread of a gradient estimator, from independent estimates of one scalar gradient
// (one per seed).
struct GradientNoise {
    double mean = 0.0;
    double standardError = 0.0;  // of the mean: the estimates' standard deviation over sqrt(n)
    // The standard deviation of one estimate over |mean|; nullopt for a zero mean.
    std::optional<double> relativeNoise;
};

// nullopt with fewer than two estimates, or where an estimate or a figure is not finite.
std::optional<GradientNoise> gradientNoise(std::span<const double> estimates);

}  // namespace vkdr
