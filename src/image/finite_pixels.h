#pragma once
#include <optional>
#include <string>

#include "image/image.h"

namespace vkdr {

// The largest magnitude a pixel of a render or of a target may have. The L2 loss adds,
// per pixel, the squared differences of image and target in three channels in float:
// 3 * (2 * 1e18)^2 = 1.2e37 stays below float's 3.4e38, with room for the sum over
// pixels, which is scaled by one over their count as it is formed.
inline constexpr float kMaxPixelMagnitude = 1e18f;

// The first pixel, in reading order, with a channel that is NaN, infinite or beyond
// kMaxPixelMagnitude, described as "pixel (12, 7) channel G is NaN"; nullopt when there
// is none.
std::optional<std::string> unrepresentablePixel(const Image& image);

// How many channel values are below 0, and the least, as "12 channel values are below 0
// (the least -0.31)"; nullopt when none is. No render has such pixels, so a target that
// does cannot be matched there.
std::optional<std::string> negativePixels(const Image& image);

// How many channel values are at the most an 8- or 16-bit image holds (1 after decoding),
// as "40 channel values are 1"; nullopt when none is. In a PNG or JPEG of a render they
// are where the render was clipped, if it was brighter there.
std::optional<std::string> valuesAtOne(const Image& image);

}  // namespace vkdr
