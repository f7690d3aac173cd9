#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/parameter_kinds.h"
#include "scene/scene.h"

namespace vkdr {

// The scene's named, overridable (and differentiable) parameters. Each kind's name
// pattern, channels and valid range are described once, in scene/parameter_kinds.h.
// materials/<material>/base_color_texture holds 3 floats per texel of the material's
// base colour texture (linear RGB, rows from the top), if it has one;
// media/<medium>/density one float per voxel of a density grid medium's grid (its box,
// x fastest, volume/density_grid.h), and media/<medium>/emission_grid the same of a
// medium's emission grid, and media/<medium>/albedo_grid 3 (RGB) per voxel of its albedo
// grid. Medium boundary materials have no base colour or emission.

// Every parameter of the scene: media in order (sigma_a, sigma_s, g each, density for a
// grid medium, emission, and emission_grid and albedo_grid where there are), then base
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

// Which of `count` values a message is about: "value 7 of 262144 (counted from 0): ", or
// nothing for a single value.
std::string whichValue(size_t index, size_t count);

// Applies "NAME=v" or "NAME=v,v,v" (the CLI's --set syntax).
void applyAssignment(Scene& scene, std::string_view assignment);

// The NAME of such an assignment; empty where it has none.
std::string_view assignedName(std::string_view assignment);

// Where a parameter's values are stored: two names give the same address exactly when
// they name the same values (the base colour textures of materials that share one
// texture); null for a parameter without values (a grid without active voxels). Throws
// vkdr::Error for an unknown name, as getParameter does.
const float* parameterStorageAddress(const Scene& scene, std::string_view name);

// The assignment with each value written as the shortest text that reads back as the
// same float ("x=0.10" and "x=1e-1" both give "x=0.1"), and a list of one value repeated
// as that value ("x=0.5,0.5,0.5" gives "x=0.5"): two assignments that set the same values
// give the same text. Throws vkdr::Error as applyAssignment does for a malformed
// one (the parameter's name is not checked).
std::string canonicalAssignment(std::string_view assignment);

// The index in Scene::densityGrids of a medium's grid of a grid kind (isGridKind): its
// density or its emission grid; -1 where it has none, or for another kind.
int32_t mediumGridOf(const Medium& medium, ParameterKind kind);

// The same for a grid parameter's name (media/<medium>/density, .../emission_grid or .../albedo_grid); -1
// for any other name, or a medium without that grid.
int32_t gridIndexOf(const Scene& scene, std::string_view name);

// The grid that a grid parameter names, as gridIndexOf; null where there is none.
const DensityGrid* densityGridOf(const Scene& scene, std::string_view name);

}  // namespace vkdr
