#include "optimize/difference_colour_map.h"

#include <algorithm>
#include <cmath>

#include "optimize/difference_image.h"

namespace vkdr {

float nearestRankPercentile(std::vector<float> values, double fraction) {
    if (values.empty()) return 0.0f;
    size_t rank = size_t(std::ceil(std::clamp(fraction, 0.0, 1.0) * double(values.size())));
    size_t index = std::clamp<size_t>(rank, 1, values.size()) - 1;
    std::nth_element(values.begin(), values.begin() + ptrdiff_t(index), values.end());
    return values[index];
}

std::array<uint8_t, 3> differenceColour(float fraction) {
    static constexpr std::array<std::array<float, 3>, 5> kStops = {{
        {0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}}};
    float at = std::clamp(std::isnan(fraction) ? 0.0f : fraction, 0.0f, 1.0f) * float(kStops.size() - 1);
    size_t below = std::min(size_t(at), kStops.size() - 2);
    float t = at - float(below);
    std::array<uint8_t, 3> colour;
    for (size_t c = 0; c < 3; ++c) {
        colour[c] = uint8_t(std::lround(kStops[below][c] + t * (kStops[below + 1][c] - kStops[below][c])));
    }
    return colour;
}

ColourMappedDifference colourMappedDifference(const Image& current, const Image& target, double percentile) {
    requireSameSize(current, target);
    const size_t pixels = size_t(current.width) * size_t(current.height);
    std::vector<float> differences(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        float largest = 0.0f;
        for (size_t c = 0; c < 3; ++c) {
            largest = std::max(largest, std::abs(current.rgb[3 * p + c] - target.rgb[3 * p + c]));
        }
        differences[p] = largest;
    }
    ColourMappedDifference mapped{current.width, current.height, std::vector<uint8_t>(pixels * 3), 0.0f};
    mapped.scale = nearestRankPercentile(differences, percentile);
    if (mapped.scale == 0.0f) mapped.scale = *std::max_element(differences.begin(), differences.end());
    for (size_t p = 0; p < pixels; ++p) {
        std::array<uint8_t, 3> colour = differenceColour(mapped.scale > 0.0f ? differences[p] / mapped.scale : 0.0f);
        std::copy(colour.begin(), colour.end(), mapped.rgb.begin() + ptrdiff_t(3 * p));
    }
    return mapped;
}

ColourBar colourBar(float scale, int width, int height) {
    ColourBar bar{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 3), {}};
    for (int x = 0; x < width; ++x) {
        // The first column shows a difference of 0, the last one of `scale`.
        std::array<uint8_t, 3> colour = differenceColour(width > 1 ? float(x) / float(width - 1) : 0.0f);
        for (int y = 0; y < height; ++y) {
            std::copy(colour.begin(), colour.end(), bar.rgb.begin() + ptrdiff_t(3 * (size_t(y) * width + x)));
        }
    }
    for (int quarter = 0; quarter <= 4; ++quarter) {
        float position = float(quarter) / 4.0f;
        bar.ticks.push_back({position, scale * position});
    }
    return bar;
}

}  // namespace vkdr
