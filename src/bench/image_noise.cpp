#include "bench/image_noise.h"

#include <cmath>

namespace vkdr {
namespace {

double luminance(const float* rgb) {
    return (double(rgb[0]) + double(rgb[1]) + double(rgb[2])) / 3.0;
}

}  // namespace

std::optional<double> relativeNoise(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        return std::nullopt;
    }
    double sumSquares = 0.0;
    size_t lit = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            const double la = luminance(a.pixel(x, y)), lb = luminance(b.pixel(x, y));
            const double mean = 0.5 * (la + lb);
            if (mean > 0.0 && std::isfinite(mean)) {
                const double deviation = (la - lb) / std::sqrt(2.0);
                sumSquares += deviation * deviation / (mean * mean);
                ++lit;
            }
        }
    }
    if (lit == 0) {
        return std::nullopt;
    }
    return std::sqrt(sumSquares / double(lit));
}

}  // namespace vkdr
