#pragma once
#include <cstddef>
#include <optional>
#include <span>
#include <string>

namespace vkdr {

// Past this many values (a texture's texels, a density grid's voxels) a parameter and its
// gradient are summarised in optimize's outputs and grad's text instead of listed: every voxel of a 64^3 grid in
// every line of log.jsonl would run to gigabytes over a run.
inline constexpr size_t kMostValuesListed = 12;

inline bool isSummarised(size_t count) { return count > kMostValuesListed; }

struct ValueSummary {
    size_t count = 0;
    double mean = 0.0;
    double minimum = 0.0;
    double maximum = 0.0;
};

ValueSummary summarise(std::span<const float> values);

// A gradient of many values, as grad prints it and log.jsonl keeps it.
struct GradientSummary {
    size_t count = 0;
    double l2Norm = 0.0;
    size_t largestAt = 0;  // the first value of largest magnitude
    double largest = 0.0;  // that value; 0 for an empty gradient
};

GradientSummary summariseGradient(std::span<const double> gradient);

// "mean 0.1234 in [0, 1.5] over 262144 values".
std::string summaryText(std::span<const float> values);

// ||values - truth|| / ||truth||, the L2 norms over every value; nothing where the sizes
// differ or the truth is all 0 (no scale to be relative to).
std::optional<double> relativeL2Error(std::span<const float> values, std::span<const float> truth);

// sqrt(mean (values - truth)^2) over every value; nothing where the sizes differ or there
// are none.
std::optional<double> rmsError(std::span<const float> values, std::span<const float> truth);

}  // namespace vkdr
