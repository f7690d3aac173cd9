#include "optimize/scene_emission_bound.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scene/scene_medium_emission.h"

namespace vkdr {

void keepSceneWideEmissionBounded(ParameterVector& parameters, const Scene& scene) {
    // The values of each coupled member that is optimised, by EmissionBoundMember.
    std::optional<std::span<double>> optimised[3];
    const std::vector<std::string>& names = parameters.names();
    for (size_t i = 0; i < names.size(); ++i) {
        if (std::optional<EmissionBoundMember> member = sceneWideEmissionMember(scene, names[i])) {
            optimised[size_t(*member)] = parameters.values().subspan(parameters.offset(i), parameters.count(i));
        }
    }
    if (!optimised[0] && !optimised[1] && !optimised[2]) return;
    const Medium& medium = *boundedSceneWideMedium(scene);
    const ValueRange unbounded{-INFINITY, INFINITY};
    for (int c = 0; c < 3; ++c) {
        const EmissionAndAttenuation sceneValues = emissionAndAttenuation(medium, c);
        double sceneValue[3] = {sceneValues.sigma_a, sceneValues.sigma_s, sceneValues.emission};
        double* value[3];
        for (size_t m = 0; m < 3; ++m) value[m] = optimised[m] ? &(*optimised[m])[size_t(c)] : &sceneValue[m];
        // The first optimised member in this order takes the whole correction.
        for (EmissionBoundMember member : kEmissionBoundMembers) {
            const size_t m = size_t(member);
            if (!optimised[m]) continue;
            ValueRange range =
                emissionBoundedRange({*value[0], *value[1], *value[2]}, member, unbounded, kEmissionBoundMargin);
            *value[m] = std::clamp(*value[m], range.lower, range.upper);
        }
    }
}

}  // namespace vkdr
