#include "optimize/density_grid_options.h"

#include <algorithm>

#include "core/error.h"
#include "scene/parameter_kinds.h"

namespace vkdr {

void requireADensityGridAmong(const std::vector<std::string>& parameters, const std::string& option) {
    const bool namesAGrid = std::any_of(parameters.begin(), parameters.end(), [](const std::string& name) {
        const std::optional<ParsedParameterName> parsed = parseParameterName(name);
        return parsed && isScalarGridKind(parsed->description->kind);
    });
    if (!namesAGrid) {
        throw Error(option + " given, but no grid (media/<medium>/density or media/<medium>/emission_grid) is being optimised");
    }
}

}  // namespace vkdr
