#pragma once
#include <algorithm>
#include <cmath>
#include <span>

namespace vkdr {

// The mean of independent estimates and its standard error: the samples' standard
// deviation (with Bessel's correction) over sqrt(n). Monte Carlo tolerances and error
// bars are built from it.
struct MeanAndError {
    double mean = 0.0;
    double error = 0.0;
};

inline MeanAndError meanAndError(std::span<const double> samples) {
    const double n = double(samples.size());
    if (samples.empty()) {
        return {};
    }
    double sum = 0.0;
    for (double x : samples) {
        sum += x;
    }
    const double mean = sum / n;
    double squaredDeviations = 0.0;
    for (double x : samples) {
        squaredDeviations += (x - mean) * (x - mean);
    }
    const double variance = samples.size() > 1 ? squaredDeviations / (n - 1.0) : 0.0;
    return {mean, std::sqrt(variance / n)};
}

}  // namespace vkdr
