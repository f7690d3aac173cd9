#pragma once
// Reading back the device's fixed-point sums (shaders/lib/fixed_point.glsl).
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "device_types.h"

namespace vkdr {

// The total of `count` fixed-point sums that lie `stride` words apart from words[0]
// (the copies of one accumulator), rounded to a double. The words' exact total decides the
// result, not how carries were spread over them, so any order of additions on the
// device gives the same bits. NaN if a term was NaN or both signs overflowed, an
// infinity if one did.
inline double fixedPointValue(std::span<const int64_t> words, size_t count = 1,
                              size_t stride = gpu::kFixedPointWordsPerSum) {
    uint64_t flags = 0;
    for (size_t i = 0; i < count; ++i) flags |= uint64_t(words[i * stride + gpu::kFixedPointFlagsWord]);
    const bool positive = flags & gpu::kFixedPointPositiveOverflow, negative = flags & gpu::kFixedPointNegativeOverflow;
    if ((flags & gpu::kFixedPointNaN) || (positive && negative)) return std::numeric_limits<double>::quiet_NaN();
    if (positive || negative) return positive ? INFINITY : -INFINITY;

    // Carry-propagate into 32-bit digits (each below 2^32) and a signed top part: the one
    // representation of the exact total.
    uint32_t digits[gpu::kFixedPointWords];
    __int128 carry = 0;
    for (uint32_t k = 0; k < gpu::kFixedPointWords; ++k) {
        __int128 total = carry;
        for (size_t i = 0; i < count; ++i) total += words[i * stride + k];
        digits[k] = uint32_t(total & 0xffffffff);
        carry = total >> 32;
    }
    long double value = static_cast<long double>(carry);
    for (uint32_t k = gpu::kFixedPointWords; k-- > 0;) value = value * 4294967296.0L + digits[k];
    return double(std::ldexp(value, gpu::kFixedPointLowestBit));
}

}  // namespace vkdr
