#include "image/finite_pixels.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace vkdr {
namespace {

std::string valueText(float value) {
    if (std::isnan(value)) {
        return "NaN";
    }
    if (std::isinf(value)) {
        return value > 0.0f ? "+infinity" : "-infinity";
    }
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, ec == std::errc() ? end : text);
}

}  // namespace

std::optional<std::string> unrepresentablePixel(const Image& image) {
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float* rgb = image.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                // Written so that NaN fails the test too.
                if (std::abs(rgb[c]) <= kMaxPixelMagnitude) {
                    continue;
                }
                std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + "RGB"[c] +
                                    " is " + valueText(rgb[c]);
                return std::isfinite(rgb[c]) ? where + ", beyond the largest magnitude a pixel may have (" + valueText(kMaxPixelMagnitude) + ")"
                                             : where;
            }
        }
    }
    return std::nullopt;
}

std::optional<std::string> negativePixels(const Image& image) {
    size_t count = 0;
    float least = 0.0f;
    for (float value : image.rgb) {
        if (value < 0.0f) {
            ++count;
            least = std::min(least, value);
        }
    }
    if (count == 0) {
        return std::nullopt;
    }
    return std::to_string(count) + (count == 1 ? " channel value is" : " channel values are") + " below 0 (the least " +
           valueText(least) + ")";
}

std::optional<std::string> valuesAtOne(const Image& image) {
    // Between the decodings of the two largest 16-bit codes (0.99996 and 1).
    constexpr float kLargestCode = 0.99999f;
    const size_t count = size_t(std::count_if(image.rgb.begin(), image.rgb.end(),
                                              [](float value) { return value >= kLargestCode; }));
    if (count == 0) {
        return std::nullopt;
    }
    return std::to_string(count) + (count == 1 ? " channel value is 1" : " channel values are 1");
}

}  // namespace vkdr
