#include "optimize/difference_image.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace vkdr {

void requireSameSize(const Image& render, const Image& target) {
    if (render.width != target.width || render.height != target.height) {
        throw Error("cannot compare a " + std::to_string(render.width) + "x" + std::to_string(render.height) +
                    " render with a " + std::to_string(target.width) + "x" + std::to_string(target.height) +
                    " target");
    }
}

DifferenceImage scaledDifference(const Image& render, const Image& target) {
    requireSameSize(render, target);
    DifferenceImage difference;
    difference.image = render;
    for (size_t i = 0; i < render.rgb.size(); ++i) {
        difference.image.rgb[i] = std::abs(render.rgb[i] - target.rgb[i]);
        difference.largestDifference = std::max(difference.largestDifference, difference.image.rgb[i]);
    }
    if (difference.largestDifference > 0.0f) {
        for (float& value : difference.image.rgb) {
            value /= difference.largestDifference;
        }
    }
    return difference;
}

}  // namespace vkdr
