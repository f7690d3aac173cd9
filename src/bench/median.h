#pragma once
#include <algorithm>
#include <vector>

namespace vkdr {

// The middle value; the mean of the two middle values for an even count; 0 for none.
inline double median(std::vector<double> values) {
    if (values.empty()) {
        return 0.0;
    }
    size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + middle, values.end());
    if (values.size() % 2 == 1) {
        return values[middle];
    }
    double below = *std::max_element(values.begin(), values.begin() + middle);
    return 0.5 * (below + values[middle]);
}

}  // namespace vkdr
