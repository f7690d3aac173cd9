#include "bench/gradient_noise.h"

#include <algorithm>
#include <cmath>

#include "core/sample_statistics.h"

namespace vkdr {

std::optional<GradientNoise> gradientNoise(std::span<const double> estimates) {
    const auto finite = [](double x) { return std::isfinite(x); };
    if (estimates.size() < 2 || !std::all_of(estimates.begin(), estimates.end(), finite)) {
        return std::nullopt;
    }
    const MeanAndError m = meanAndError(estimates);
    if (!finite(m.mean) || !finite(m.error)) {
        return std::nullopt;
    }
    GradientNoise noise{m.mean, m.error, std::nullopt};
    const double relative = m.error * std::sqrt(double(estimates.size())) / std::abs(m.mean);
    if (m.mean != 0.0 && finite(relative)) {
        noise.relativeNoise = relative;
    }
    return noise;
}

}  // namespace vkdr
