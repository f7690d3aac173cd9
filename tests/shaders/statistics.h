#pragma once
#include <cmath>
#include <vector>

namespace vkdr::test {

// Critical value of the chi-square distribution with `dof` degrees of freedom that a
// correct sampler exceeds with probability 1e-6 (Wilson-Hilferty approximation).
inline double chiSquareCritical(int dof) {
    constexpr double z = 4.753;  // standard normal quantile of 1 - 1e-6
    double k = dof;
    double c = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
    return k * c * c * c;
}

// Pearson's statistic of observed counts against expected counts; bins expecting fewer
// than 5 samples are pooled, as the approximation requires.
inline double chiSquare(const std::vector<double>& observed, const std::vector<double>& expected, int* dof) {
    double statistic = 0.0, pooledObserved = 0.0, pooledExpected = 0.0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooledObserved += observed[i];
            pooledExpected += expected[i];
            continue;
        }
        statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooledExpected >= 5.0) {
        statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++bins;
    }
    *dof = bins - 1;
    return statistic;
}

}  // namespace vkdr::test
