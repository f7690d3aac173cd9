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
    // The values of each coupled member (sigma_a, sigma_s, emission) that is optimised.
    std::optional<std::span<double>> optimised[3];
    const char* const members[3] = {"sigma_a", "sigma_s", "emission"};
    const std::vector<std::string>& names = parameters.names();
    for (size_t i = 0; i < names.size(); ++i) {
        std::optional<std::string> member = sceneWideEmissionMember(scene, names[i]);
        if (!member) continue;
        size_t m = size_t(std::find(members, members + 3, *member) - members);
        optimised[m] = parameters.values().subspan(parameters.offset(i), parameters.count(i));
    }
    if (!optimised[0] && !optimised[1] && !optimised[2]) return;
    const Medium& medium = scene.media[size_t(scene.sceneMedium)];
    const ValueRange unbounded{-INFINITY, INFINITY};
    for (size_t c = 0; c < 3; ++c) {
        double* value[3];
        double sceneValue[3] = {medium.sigma_a[c], medium.sigma_s[c], medium.emission[c]};
        for (size_t m = 0; m < 3; ++m) value[m] = optimised[m] ? &(*optimised[m])[c] : &sceneValue[m];
        // The first optimised member in this order takes the whole correction.
        for (size_t m = 0; m < 3; ++m) {
            if (!optimised[m]) continue;
            ValueRange range = emissionBoundedRange({*value[0], *value[1], *value[2]}, members[m], unbounded,
                                                    kEmissionBoundMargin);
            *value[m] = std::clamp(*value[m], range.lower, range.upper);
        }
    }
}

}  // namespace vkdr
