#include "optimize/value_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/format_text.h"

namespace vkdr {

namespace {

// A grid's millions of values are summarised in every iteration, so the sums run in
// parallel, over fixed blocks combined in a fixed order: the same bits on any number of
// threads.
constexpr size_t kValuesPerBlock = size_t(1) << 16;

template <typename Partial, typename Accumulate, typename Combine>
Partial reduceInBlocks(size_t count, Partial identity, Accumulate accumulate, Combine combine) {
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, count, kValuesPerBlock), identity,
        [&](const tbb::blocked_range<size_t>& block, Partial partial) {
            for (size_t i = block.begin(); i < block.end(); ++i) accumulate(partial, i);
            return partial;
        },
        combine);
}

struct ValueTotals {
    double sum = 0.0;
    double minimum = std::numeric_limits<double>::infinity();
    double maximum = -std::numeric_limits<double>::infinity();
};

struct GradientTotals {
    double sumOfSquares = 0.0;
    size_t largestAt = 0;
    double largestMagnitude = -1.0;  // below every magnitude, so the first value replaces it
};

struct ErrorTotals {
    double error = 0.0;
    double norm = 0.0;
};

}  // namespace

ValueSummary summarise(std::span<const float> values) {
    ValueSummary summary;
    summary.count = values.size();
    if (values.empty()) return summary;
    const ValueTotals totals = reduceInBlocks(
        values.size(), ValueTotals{},
        [&](ValueTotals& partial, size_t i) {
            partial.sum += values[i];
            partial.minimum = std::min(partial.minimum, double(values[i]));
            partial.maximum = std::max(partial.maximum, double(values[i]));
        },
        [](ValueTotals left, const ValueTotals& right) {
            return ValueTotals{left.sum + right.sum, std::min(left.minimum, right.minimum),
                               std::max(left.maximum, right.maximum)};
        });
    summary.mean = totals.sum / double(values.size());
    summary.minimum = totals.minimum;
    summary.maximum = totals.maximum;
    return summary;
}

GradientSummary summariseGradient(std::span<const double> gradient) {
    GradientSummary summary;
    summary.count = gradient.size();
    const GradientTotals totals = reduceInBlocks(
        gradient.size(), GradientTotals{},
        [&](GradientTotals& partial, size_t i) {
            partial.sumOfSquares += gradient[i] * gradient[i];
            if (std::abs(gradient[i]) > partial.largestMagnitude) {
                partial.largestMagnitude = std::abs(gradient[i]);
                partial.largestAt = i;
            }
        },
        // The left block holds the lower indices: it keeps a tie.
        [](GradientTotals left, const GradientTotals& right) {
            left.sumOfSquares += right.sumOfSquares;
            if (right.largestMagnitude > left.largestMagnitude) {
                left.largestMagnitude = right.largestMagnitude;
                left.largestAt = right.largestAt;
            }
            return left;
        });
    summary.l2Norm = std::sqrt(totals.sumOfSquares);
    summary.largestAt = totals.largestAt;
    summary.largest = gradient.empty() ? 0.0 : gradient[summary.largestAt];
    return summary;
}

std::string summaryText(std::span<const float> values) {
    const ValueSummary summary = summarise(values);
    return formatText("mean %.4g in [%.4g, %.4g] over %zu values", summary.mean, summary.minimum, summary.maximum,
                      summary.count);
}

namespace {

// ||values - truth||^2 and ||truth||^2; the spans are the same size.
ErrorTotals errorTotals(std::span<const float> values, std::span<const float> truth) {
    return reduceInBlocks(
        values.size(), ErrorTotals{},
        [&](ErrorTotals& partial, size_t i) {
            const double difference = double(values[i]) - double(truth[i]);
            partial.error += difference * difference;
            partial.norm += double(truth[i]) * double(truth[i]);
        },
        [](const ErrorTotals& left, const ErrorTotals& right) {
            return ErrorTotals{left.error + right.error, left.norm + right.norm};
        });
}

}  // namespace

std::optional<double> relativeL2Error(std::span<const float> values, std::span<const float> truth) {
    if (values.size() != truth.size()) return std::nullopt;
    const ErrorTotals totals = errorTotals(values, truth);
    if (totals.norm == 0.0) return std::nullopt;
    return std::sqrt(totals.error / totals.norm);
}

std::optional<double> rmsError(std::span<const float> values, std::span<const float> truth) {
    if (values.size() != truth.size() || values.empty()) return std::nullopt;
    return std::sqrt(errorTotals(values, truth).error / double(values.size()));
}

}  // namespace vkdr
