#include "scene/scene_medium_emission.h"

#include <algorithm>
#include <limits>

#include "core/format_text.h"

namespace vkdr {

const Medium* boundedSceneWideMedium(const Scene& scene) {
    if (scene.sceneMedium == kNoMedium) return nullptr;
    const Medium& medium = scene.media[size_t(scene.sceneMedium)];
    if (medium.isHeterogeneous() || medium.hasEmissionGrid()) return nullptr;
    return &medium;
}

EmissionAndAttenuation emissionAndAttenuation(const Medium& medium, int channel) {
    return {medium.sigma_a[channel], medium.sigma_s[channel], medium.emission[channel]};
}

std::optional<UnboundedSceneEmission> unboundedSceneEmission(const Scene& scene) {
    const Medium* bounded = boundedSceneWideMedium(scene);
    if (!bounded) return std::nullopt;
    const Medium& medium = *bounded;
    for (int c = 0; c < 3; ++c) {
        const double emission = medium.emission[c];
        const double sigmaT = double(medium.sigma_a[c]) + double(medium.sigma_s[c]);
        if (!(emission > 0.0) || emission <= kMaxRadiance * sigmaT) continue;
        const std::string prefix = "media/" + medium.name + "/";
        if (sigmaT == 0.0) {
            return UnboundedSceneEmission{
                c, formatText("the scene-wide medium emits %s[%d] = %g where it neither absorbs nor scatters "
                              "(%ssigma_a + sigma_s = 0), which makes every ray that leaves the scene infinitely "
                              "bright",
                              (prefix + "emission").c_str(), c, emission, prefix.c_str())};
        }
        // As many digits as a float's value needs: values a user gave as 6e10 and 0.06
        // are the floats 6.0000002e10 and 0.0599999987, over the bound by their rounding.
        return UnboundedSceneEmission{
            c, formatText("the scene-wide medium gives every ray that leaves the scene %semission / (sigma_a + "
                          "sigma_s) = %.9g / %.9g = %.9g in channel %d, beyond the %g a radiance may have",
                          prefix.c_str(), emission, sigmaT, emission / sigmaT, c, kMaxRadiance)};
    }
    return std::nullopt;
}

std::optional<EmissionBoundMember> sceneWideEmissionMember(const Scene& scene, std::string_view parameter) {
    const Medium* medium = boundedSceneWideMedium(scene);
    if (!medium) return std::nullopt;
    const std::string prefix = "media/" + medium->name + "/";
    const char* const names[] = {"sigma_a", "sigma_s", "emission"};
    for (EmissionBoundMember member : kEmissionBoundMembers) {
        if (parameter == prefix + names[size_t(member)]) return member;
    }
    return std::nullopt;
}

ValueRange emissionBoundedRange(const EmissionAndAttenuation& values, EmissionBoundMember member, ValueRange range,
                                double margin) {
    if (member == EmissionBoundMember::Emission) {
        range.upper = std::min(range.upper, kMaxRadiance * (values.sigma_a + values.sigma_s) / (1.0 + margin));
        return range;
    }
    if (!(values.emission > 0.0)) return range;
    // At least float's least normal number: a smaller one loses the margin when stored.
    const double attenuation = std::max(values.emission / kMaxRadiance * (1.0 + margin),
                                        double(std::numeric_limits<float>::min()));
    const double other = member == EmissionBoundMember::SigmaA ? values.sigma_s : values.sigma_a;
    range.lower = std::max(range.lower, attenuation - other);
    return range;
}

}  // namespace vkdr
