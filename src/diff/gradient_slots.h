#pragma once
#include <span>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "scene/parameter_kinds.h"
#include "scene/scene.h"

namespace vkdr {

// Where a named parameter's gradient sits among the adjoint pass's accumulators: `groups`
// groups of the kind's channels in `accumulator`, the first at `first`, each `stride`
// floats after the one before (a texture's texels, 4 floats each).
struct GradientSlot {
    std::string name;
    ParameterKind kind;
    std::vector<float> SceneGradients::*accumulator;
    size_t first = 0;
    size_t groups = 1;
    size_t stride = 0;

    // The parameter's floats: one gradient value each.
    size_t valueCount() const { return groups * describe(kind).channels; }
};

// Whether the adjoint has a gradient for the medium's sigma_s: not a density grid's with
// a channel at 0, whose scattering no path samples.
bool hasSigmaSGradient(const Medium& medium);

// Resolves names like media/fog/sigma_a; an unknown name is a vkdr::Error listing the
// valid ones (scene/parameters.h), and so are a name given twice and two names of the
// same values (a texture that two materials share).
std::vector<GradientSlot> resolveGradientSlots(const Scene& scene, const std::vector<std::string>& names);

// The kinds of gradient these slots need (render/renderer.h, DerivativeTargets): only
// the kinds of parameter among them.
DerivativeTargets derivativeTargetsOf(const std::vector<GradientSlot>& slots);

// The parameter's gradient, one value per float of the parameter (scene/parameters.h).
std::vector<double> gatherGradient(const GradientSlot& slot, const SceneGradients& gradients);

// Adds `weight` times the parameter's gradient to `sum` (one value per float of the
// parameter) in one pass: a grid's millions of voxels cross in every iteration.
void addWeightedGradient(const GradientSlot& slot, const SceneGradients& gradients, double weight,
                         std::span<double> sum);

}  // namespace vkdr
