#include "diff/gradient_check.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "core/sample_statistics.h"
#include "diff/gradient_over_seeds.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "scene/scene_medium_emission.h"

namespace vkdr {
namespace {

// The adjoint's gradient at seed s is taken from the render at seed s; the finite
// differences use seeds from here on, so the two estimates are independent and their
// standard errors combine as those of independent means.
constexpr uint32_t kFirstFiniteDifferenceSeed = 1u << 20;

double lossWith(RenderedLossGradient& lg, const Scene& scene, const std::string& name, int component, float value,
                uint32_t seed) {
    Scene changed = scene;
    std::vector<float> v = getParameter(changed, name);
    v[component] = value;
    setParameter(changed, name, v);
    return lg.loss(changed, seed);
}

// dL/dx by a central difference, or near a bound by the second-order one-sided
// difference that stays inside it. The largest float bounds every range: a parameter set
// is a float.
double finiteDifference(const std::function<double(double)>& loss, double x, double h, const ValueRange& range) {
    if (x - h < range.lower) {
        return (-3.0 * loss(x) + 4.0 * loss(x + h) - loss(x + 2.0 * h)) / (2.0 * h);
    }
    if (x + h > std::min(range.upper, double(std::numeric_limits<float>::max()))) {
        return (3.0 * loss(x) - 4.0 * loss(x - h) + loss(x - 2.0 * h)) / (2.0 * h);
    }
    return (loss(x + h) - loss(x - h)) / (2.0 * h);
}

}  // namespace

std::vector<GradientCheckRow> checkGradients(RenderedLossGradient& lg, const Scene& scene,
                                             const std::vector<std::string>& parameters, int seeds) {
    const std::vector<std::vector<MeanAndError>> adjoint = gradientOverSeeds(lg, scene, uint32_t(seeds));
    std::vector<GradientCheckRow> rows;
    for (size_t p = 0; p < parameters.size(); ++p) {
        const std::vector<float> value = getParameter(scene, parameters[p]);
        const ParameterDescription& description = *parseParameterName(parameters[p])->description;
        const std::optional<EmissionBoundMember> coupled = sceneWideEmissionMember(scene, parameters[p]);
        for (size_t c = 0; c < value.size(); ++c) {
            const float x = value[c];
            const double h = description.finiteDifferenceStep(x);
            ValueRange range = description.range;
            if (coupled) {
                // The optimiser's margin: the steps are rendered as floats.
                range = emissionBoundedRange(emissionAndAttenuation(*boundedSceneWideMedium(scene), int(c)),
                                             *coupled, range, kEmissionBoundMargin);
            }
            std::vector<double> differences;
            for (int s = 0; s < seeds; ++s) {
                const uint32_t seed = kFirstFiniteDifferenceSeed + uint32_t(s);
                auto loss = [&](double at) { return lossWith(lg, scene, parameters[p], int(c), float(at), seed); };
                differences.push_back(finiteDifference(loss, x, h, range));
            }
            const MeanAndError& a = adjoint[p][c];
            const MeanAndError f = meanAndError(differences);
            rows.push_back({parameters[p], int(c), a.mean, a.error, f.mean, f.error, h});
        }
    }
    return rows;
}

}  // namespace vkdr
