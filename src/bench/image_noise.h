#pragma once
#include <optional>

#include "image/image.h"

namespace vkdr {

// The per-pixel relative noise of a render, from two renders that differ only in the
// seed: for each pixel with a mean luminance m > 0 over the pair, the standard deviation
// of one render's luminance, |a - b| / sqrt(2), over m; then the root mean square over
// those pixels. nullopt when no pixel has light, or the images differ in size.
std::optional<double> relativeNoise(const Image& a, const Image& b);

}  // namespace vkdr
