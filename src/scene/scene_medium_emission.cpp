#include "scene/scene_medium_emission.h"

#include "core/format_text.h"
#include "scene/parameter_kinds.h"

namespace vkdr {

std::optional<UnboundedSceneEmission> unboundedSceneEmission(const Scene& scene) {
    if (scene.sceneMedium == kNoMedium) return std::nullopt;
    const Medium& medium = scene.media[size_t(scene.sceneMedium)];
    if (medium.isHeterogeneous() || medium.hasEmissionGrid()) return std::nullopt;
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
        return UnboundedSceneEmission{
            c, formatText("the scene-wide medium gives every ray that leaves the scene %semission / (sigma_a + "
                          "sigma_s) = %g / %g = %g in channel %d, beyond the %g a radiance may have",
                          prefix.c_str(), emission, sigmaT, emission / sigmaT, c, kMaxRadiance)};
    }
    return std::nullopt;
}

}  // namespace vkdr
