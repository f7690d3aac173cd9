#include "diff/gradient_check.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/format_text.h"
#include "core/sample_statistics.h"
#include "diff/gradient_over_seeds.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "scene/scene_medium_emission.h"

namespace vkdr {
namespace {

// The adjoint's gradient at seed s is taken from the render at seed s; the finite
// differences use seeds this far on, so the two estimates are independent and their
// standard errors combine as those of independent means.
constexpr uint32_t kFiniteDifferenceSeedOffset = 1u << 20;

double lossWith(RenderedLossGradient& lg, const Scene& scene, const std::string& name, int component, float value,
                uint32_t seed) {
    Scene changed = scene;
    std::vector<float> v = getParameter(changed, name);
    v[component] = value;
    setParameter(changed, name, v);
    return lg.loss(changed, seed);
}

// The largest float bounds every range: a parameter set is a float.
double upperEnd(const ValueRange& range) {
    return std::min(range.upper, double(std::numeric_limits<float>::max()));
}

// The step h where it fits in the range around x, as a central or a one-sided
// difference (2h to one side); where it fits neither way (a range narrower than the
// step, as a scene-wide medium's emission bound can make), half the wider side's room.
double fittedStep(double x, double h, const ValueRange& range) {
    const double below = x - range.lower, above = upperEnd(range) - x;
    if ((h <= below && h <= above) || 2.0 * h <= below || 2.0 * h <= above) return h;
    return std::max(below, above) / 2.0;
}

// dL/dx by a central difference, or near a bound by the second-order one-sided
// difference that stays inside it; h from fittedStep.
double finiteDifference(const std::function<double(double)>& loss, double x, double h, const ValueRange& range) {
    if (x - h < range.lower) {
        return (-3.0 * loss(x) + 4.0 * loss(x + h) - loss(x + 2.0 * h)) / (2.0 * h);
    }
    if (x + h > upperEnd(range)) {
        return (3.0 * loss(x) - 4.0 * loss(x - h) + loss(x - 2.0 * h)) / (2.0 * h);
    }
    return (loss(x + h) - loss(x - h)) / (2.0 * h);
}

}  // namespace

std::vector<std::vector<FiniteDifferenceStep>> finiteDifferenceSteps(const Scene& scene,
                                                                      const std::vector<std::string>& parameters) {
    std::vector<std::vector<FiniteDifferenceStep>> steps;
    for (const std::string& name : parameters) {
        const std::vector<float> value = getParameter(scene, name);
        const ParameterDescription& description = *parseParameterName(name)->description;
        const std::optional<EmissionBoundMember> coupled = sceneWideEmissionMember(scene, name);
        std::vector<FiniteDifferenceStep>& components = steps.emplace_back();
        for (size_t c = 0; c < value.size(); ++c) {
            const float x = value[c];
            ValueRange range = description.range;
            if (coupled) {
                // The optimiser's margin: the steps are rendered as floats.
                range = emissionBoundedRange(emissionAndAttenuation(*boundedSceneWideMedium(scene), int(c)),
                                             *coupled, range, kEmissionBoundMargin);
            }
            const double h = fittedStep(x, description.finiteDifferenceStep(x), range);
            if (!(float(x + h) != x || float(x - h) != x)) {
                throw Error(formatText("--check: %s[%zu] = %g has no room for a finite difference: a step of %g "
                                       "leaves it unchanged as a float, in its range here of %g to %g%s",
                                       name.c_str(), c, double(x), h, range.lower, upperEnd(range),
                                       coupled ? " (a scene-wide medium's emission / (sigma_a + sigma_s) may not "
                                                 "exceed 1e12)"
                                               : ""));
            }
            components.push_back({h, range});
        }
    }
    return steps;
}

size_t gradientCheckSteps(const Scene& scene, const std::vector<std::string>& parameters, int seeds) {
    size_t values = 0;
    for (const std::string& name : parameters) values += getParameter(scene, name).size();
    return size_t(seeds) * (1 + values);
}

std::vector<GradientCheckRow> checkGradients(RenderedLossGradient& lg, const Scene& scene,
                                             const std::vector<std::string>& parameters, int seeds,
                                             uint32_t firstSeed, const std::function<void(double)>& progress,
                                             const GradientResult* atFirstSeed) {
    const std::vector<std::vector<FiniteDifferenceStep>> steps = finiteDifferenceSteps(scene, parameters);
    const double total = double(gradientCheckSteps(scene, parameters, seeds));
    double done = atFirstSeed ? 1.0 : 0.0;
    auto stepDone = [&] {
        done += 1.0;
        if (progress) progress(done / total);
    };
    // Within each of the adjoint's evaluations too, the longest steps; unset when this
    // call ends, since the callback refers to its count.
    struct ProgressUnset {
        RenderedLossGradient& lg;
        ~ProgressUnset() { lg.reportProgress({}); }
    } unset{lg};
    if (progress) lg.reportProgress([&](double fraction) { progress((done + fraction) / total); });
    const std::vector<std::vector<MeanAndError>> adjoint =
        gradientOverSeeds(lg, scene, uint32_t(seeds), firstSeed, stepDone, atFirstSeed);
    std::vector<GradientCheckRow> rows;
    for (size_t p = 0; p < parameters.size(); ++p) {
        const std::vector<float> value = getParameter(scene, parameters[p]);
        for (size_t c = 0; c < value.size(); ++c) {
            const float x = value[c];
            const double h = steps[p][c].step;
            const ValueRange& range = steps[p][c].range;
            std::vector<double> differences;
            bool resolved = false;
            for (int s = 0; s < seeds; ++s) {
                const uint32_t seed = firstSeed + kFiniteDifferenceSeedOffset + uint32_t(s);
                std::optional<double> firstLoss;
                auto loss = [&](double at) {
                    const double l = lossWith(lg, scene, parameters[p], int(c), float(at), seed);
                    resolved = resolved || (firstLoss && l != *firstLoss);
                    firstLoss = firstLoss.value_or(l);
                    return l;
                };
                differences.push_back(finiteDifference(loss, x, h, range));
                stepDone();
            }
            const MeanAndError& a = adjoint[p][c];
            const MeanAndError f = meanAndError(differences);
            rows.push_back({parameters[p], int(c), a.mean, a.error, f.mean, f.error, h, resolved});
        }
    }
    return rows;
}

}  // namespace vkdr
