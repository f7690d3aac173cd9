#pragma once
#include "optimize/parameter_vector.h"
#include "scene/scene.h"

namespace vkdr {

// A homogeneous scene-wide medium gives every ray that leaves the scene emission /
// (sigma_a + sigma_s), which the scene may not let exceed kMaxRadiance
// (scene/scene_medium_emission.h). A step can break that with values each within its own
// bounds (sigma_a and sigma_s both clamped to 0 while the medium emits, or an emission
// stepped up). This holds the step back inside the bound, channel by channel: the first
// optimised of sigma_a, sigma_s and emission takes the whole correction, a sigma raised
// until sigma_a + sigma_s = emission / kMaxRadiance, an emission lowered to
// kMaxRadiance x (sigma_a + sigma_s). Values of `scene` stand in for the medium's
// parameters that are not optimised.
void keepSceneWideEmissionBounded(ParameterVector& parameters, const Scene& scene);

}  // namespace vkdr
