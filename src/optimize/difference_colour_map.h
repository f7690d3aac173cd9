#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "image/image.h"

namespace vkdr {

// The report's difference images: each pixel's largest channel difference
// |current - target|, in false colour on a scale set by a high percentile of those
// differences rather than by the brightest pixel, so that a few firefly pixels do not
// turn the rest black.

// The nearest-rank percentile: the smallest value with at least `fraction` of `values`
// at or below it (fraction in (0, 1]). 0 for no values.
float nearestRankPercentile(std::vector<float> values, double fraction);

// The colour of a difference at `fraction` of the scale (clamped to [0, 1]): a
// sequential map from black through purple and orange to pale yellow (matplotlib's
// inferno at quarter steps, interpolated linearly), legible in greyscale too.
std::array<uint8_t, 3> differenceColour(float fraction);

struct ColourMappedDifference {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;  // width * height * 3, display colours
    // The difference the top of the colour map stands for: the percentile of the
    // pixels' differences, or the largest difference when that percentile is 0 (almost
    // every pixel matches); 0 only for identical images.
    float scale = 0.0f;
};

// Throws vkdr::Error when the sizes differ.
ColourMappedDifference colourMappedDifference(const Image& current, const Image& target, double percentile);

struct ColourBarTick {
    float position = 0.0f;  // along the bar, 0 (left) to 1 (right)
    float value = 0.0f;     // the difference that colour stands for
};

struct ColourBar {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;          // the colour map from left to right
    std::vector<ColourBarTick> ticks;  // 0, 1/4, ... of `scale`; the last colour also shows larger differences
};

ColourBar colourBar(float scale, int width = 256, int height = 14);

}  // namespace vkdr
