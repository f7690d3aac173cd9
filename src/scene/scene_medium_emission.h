#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "scene/parameter_kinds.h"
#include "scene/scene.h"

namespace vkdr {

// A homogeneous scene-wide medium fills all space: a ray that leaves the scene through
// it gathers emission / (sigma_a + sigma_s) in each channel, infinite where it emits
// without attenuating. Where that exceeds kMaxRadiance in a channel: that channel, and
// what is wrong, naming the medium's parameters. A density or emission grid is finite.
struct UnboundedSceneEmission {
    int channel = 0;
    std::string problem;
};
std::optional<UnboundedSceneEmission> unboundedSceneEmission(const Scene& scene);

// The homogeneous scene-wide medium without an emission grid, the medium the bound
// applies to; nullptr where the scene has none.
const Medium* boundedSceneWideMedium(const Scene& scene);

// The three values the bound couples, in the order keepSceneWideEmissionBounded
// (optimize/scene_emission_bound.h) corrects them.
enum class EmissionBoundMember { SigmaA, SigmaS, Emission };
inline constexpr EmissionBoundMember kEmissionBoundMembers[] = {
    EmissionBoundMember::SigmaA, EmissionBoundMember::SigmaS, EmissionBoundMember::Emission};

// One channel of those values.
struct EmissionAndAttenuation {
    double sigma_a = 0.0;
    double sigma_s = 0.0;
    double emission = 0.0;
};
EmissionAndAttenuation emissionAndAttenuation(const Medium& medium, int channel);

// The member `parameter` names where it is one of boundedSceneWideMedium's coupled values;
// else nullopt.
std::optional<EmissionBoundMember> sceneWideEmissionMember(const Scene& scene, std::string_view parameter);

// A margin for emissionBoundedRange far above float's rounding (6e-8, relative).
inline constexpr double kEmissionBoundMargin = 1e-5;

// `range` narrowed to the values of `member` that keep emission / (sigma_a + sigma_s)
// within kMaxRadiance, the other two as in `values`: a least sigma_a or sigma_s, a
// largest emission. `margin` (relative) holds the values that far inside the bound, so
// that they stay inside it once stored as floats.
ValueRange emissionBoundedRange(const EmissionAndAttenuation& values, EmissionBoundMember member, ValueRange range,
                                double margin);

}  // namespace vkdr
