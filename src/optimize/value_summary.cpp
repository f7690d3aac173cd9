#include "optimize/value_summary.h"

#include <algorithm>
#include <cmath>

#include "core/format_text.h"

namespace vkdr {

ValueSummary summarise(std::span<const float> values) {
    ValueSummary summary;
    summary.count = values.size();
    if (values.empty()) return summary;
    double sum = 0.0;
    summary.minimum = summary.maximum = values[0];
    for (float value : values) {
        sum += value;
        summary.minimum = std::min(summary.minimum, double(value));
        summary.maximum = std::max(summary.maximum, double(value));
    }
    summary.mean = sum / double(values.size());
    return summary;
}

GradientSummary summariseGradient(std::span<const double> gradient) {
    GradientSummary summary;
    summary.count = gradient.size();
    double sumOfSquares = 0.0;
    for (size_t i = 0; i < gradient.size(); ++i) {
        sumOfSquares += gradient[i] * gradient[i];
        if (std::abs(gradient[i]) > std::abs(gradient[summary.largestAt])) summary.largestAt = i;
    }
    summary.l2Norm = std::sqrt(sumOfSquares);
    summary.largest = gradient.empty() ? 0.0 : gradient[summary.largestAt];
    return summary;
}

std::string summaryText(std::span<const float> values) {
    const ValueSummary summary = summarise(values);
    return formatText("mean %.4g in [%.4g, %.4g] over %zu values", summary.mean, summary.minimum, summary.maximum,
                      summary.count);
}

std::optional<double> relativeL2Error(std::span<const float> values, std::span<const float> truth) {
    if (values.size() != truth.size()) return std::nullopt;
    double error = 0.0, norm = 0.0;
    for (size_t i = 0; i < values.size(); ++i) {
        const double difference = double(values[i]) - double(truth[i]);
        error += difference * difference;
        norm += double(truth[i]) * double(truth[i]);
    }
    if (norm == 0.0) return std::nullopt;
    return std::sqrt(error / norm);
}

}  // namespace vkdr
