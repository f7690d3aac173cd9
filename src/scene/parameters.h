#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// The scene's named, overridable (and differentiable) parameters. Each kind's name
// pattern, channels and valid range are described once, in scene/parameter_kinds.h.
// materials/<material>/base_color_texture holds 3 floats per texel of the material's
// base colour texture (linear RGB, rows from the top), if it has one;
// media/<medium>/density one float per voxel of a density grid medium's grid (its box,
// x fastest, volume/density_grid.h). Medium boundary
// materials have no base colour or emission.

// Every parameter of the scene: media in order (sigma_a, sigma_s, g each, and density for
// a grid medium), then base
// colours, then the emissions of emissive materials, then the punctual lights' intensities.
std::vector<std::string> parameterNames(const Scene& scene);

// The current value (3 floats, 1 for g, 3 per texel for a texture, 1 per voxel). Throws vkdr::Error for an unknown name,
// listing the valid ones.
std::vector<float> getParameter(const Scene& scene, std::string_view name);

// Sets a parameter; one value sets every channel (and texel) of the parameter. Throws
// vkdr::Error naming the parameter when the value is out of range or not finite.
// lights/<material>/emission is accepted for every surface material, not only the
// emissive ones listed by parameterNames, so an emission driven to 0 can be raised again.
void setParameter(Scene& scene, std::string_view name, std::span<const float> values);

// Applies "NAME=v" or "NAME=v,v,v" (the CLI's --set syntax).
void applyAssignment(Scene& scene, std::string_view assignment);

// The grid that a density parameter (media/<medium>/density) names; null for any other
// name, or a medium without a grid.
const DensityGrid* densityGridOf(const Scene& scene, std::string_view name);

}  // namespace vkdr
