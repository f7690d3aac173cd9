#pragma once
#include <algorithm>
#include <cmath>

namespace vkdr {

// The sRGB transfer functions (IEC 61966-2-1), exact piecewise forms.
inline float srgbFromLinear(float linear) {
    // Clamp first: the curve is only defined on [0, 1]; NaN becomes 0.
    float v = linear > 0.0f ? std::min(linear, 1.0f) : 0.0f;
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

inline float linearFromSrgb(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace vkdr
