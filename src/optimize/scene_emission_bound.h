#pragma once
#include "optimize/parameter_vector.h"
#include "scene/scene.h"

namespace vkdr {

// A homogeneous scene-wide medium gives every ray that leaves the scene emission /
// (sigma_a + sigma_s), which the scene may not let exceed kMaxRadiance
// (scene/scene_medium_emission.h). A step can break that with values each within its own
// bounds: sigma_a and sigma_s both clamped to 0 while the medium emits. This holds the
// step back to the nearest values that keep it bounded, channel by channel: sigma_a (or,
// where only sigma_s is optimised, sigma_s) is raised until sigma_a + sigma_s =
// emission / kMaxRadiance; where only the emission is optimised, it is lowered to
// kMaxRadiance x (sigma_a + sigma_s). Values of `scene` stand in for the medium's
// parameters that are not optimised.
void keepSceneWideEmissionBounded(ParameterVector& parameters, const Scene& scene);

}  // namespace vkdr
