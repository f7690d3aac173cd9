#include "optimize/constraints.h"

#include <algorithm>
#include <limits>
#include <string>

#include "core/error.h"

namespace vkdr {

ValueBounds boundsForParameter(std::string_view name) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    std::string_view field = name.substr(name.rfind('/') + 1);
    if (field == "sigma_a" || field == "sigma_s" || field == "emission") return {0.0, kInfinity};
    if (field == "g") return {-kMaxAbsAnisotropy, kMaxAbsAnisotropy};
    if (field == "base_color" || field == "base_color_texture") return {0.0, 1.0};
    throw Error("parameter '" + std::string(name) +
                "' cannot be optimised: expected a name ending in sigma_a, sigma_s, g, base_color, "
                "base_color_texture or emission");
}

void projectOntoBounds(std::span<double> values, const ValueBounds& bounds) {
    for (double& value : values) {
        value = std::clamp(value, bounds.lower, bounds.upper);
    }
}

}  // namespace vkdr
