#include "optimize/constraints.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/error.h"

namespace vkdr {

ValueRange boundsForParameter(std::string_view name) {
    if (std::optional<ParsedParameterName> parsed = parseParameterName(name)) {
        return parsed->description->range;
    }
    std::string patterns;
    for (const ParameterDescription& description : parameterDescriptions()) {
        patterns += (patterns.empty() ? "" : ", ") + parameterPattern(description);
    }
    throw Error("parameter '" + std::string(name) + "' cannot be optimised: expected one of " + patterns);
}

void projectOntoBounds(std::span<double> values, const ValueRange& bounds) {
    for (double& value : values) {
        value = std::clamp(value, bounds.lower, bounds.upper);
    }
}

}  // namespace vkdr
