#pragma once
#include <string>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"

namespace vkdr {

// Where a named parameter's gradient lives in the adjoint pass's accumulators.
struct ParameterSlot {
    enum class Kind { SigmaA, SigmaS, PhaseG, BaseColor, BaseColorTexture, Emission };
    std::string name;
    Kind kind;
    uint32_t index;  // medium or material; for BaseColorTexture, the texture's first texel
    uint32_t texelCount = 0;
};

// Resolves names like media/fog/sigma_a; an unknown name is a vkdr::Error listing the
// valid ones (scene/parameters.h).
std::vector<ParameterSlot> resolveParameterSlots(const Scene& scene, const std::vector<std::string>& names);

std::vector<double> gatherGradient(const ParameterSlot& slot, const SceneGradients& gradients);

}  // namespace vkdr
