#pragma once
#include <optional>
#include <string>

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

}  // namespace vkdr
