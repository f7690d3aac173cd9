#pragma once
#include <filesystem>

#include "scene/scene.h"

namespace vkdr {

// Writes `out` (a .gltf) as a copy of `original` (.gltf or .glb) with every named
// parameter of `scene` (scene/parameters.h) written back, `scene` having been loaded
// from `original` and only its parameters changed since:
// - a medium keeps its spelling where it can: VKDR_participating_media as is;
//   KHR_materials_volume gets the attenuationColor/Distance that give sigma_a, and the
//   material gains VKDR_participating_media (which takes precedence when loading) once
//   sigma_s or g is not 0, since the Khronos spelling absorbs only;
// - the scene medium, baseColorFactor (alpha kept), and emissiveFactor with
//   KHR_materials_emissive_strength so that factor * strength = emission, factor <= 1.
// - the texels of base colour textures, as <stem>.image<i>.png beside `out` (8-bit
//   sRGB, alpha dropped), which the image then refers to;
// - density grids with their current voxels, as <stem>.materials<i>.density.vdb (or
//   <stem>.density.vdb for the scene medium) beside `out`, which "density" then names.
// External buffers and images are referred to by URIs rewritten relative to `out`'s
// directory; a .glb's binary chunk is written beside `out` as <stem>.bin. Files are
// written atomically. Throws vkdr::Error naming the file at fault, among them an
// original, buffer or image that has changed since `scene` was loaded from it
// (Scene::sourceFiles), any file to be written that is one the scene reads (a grid
// included), and a scene its loader would refuse; all of that before any file is written.
void writeSceneWithParameters(const std::filesystem::path& original, const Scene& scene,
                              const std::filesystem::path& out);

// Throws vkdr::Error naming the grid file whose grid writeSceneWithParameters could not
// write back for its transform (a NanoVDB grid's voxels smaller than OpenVDB holds,
// gridTransformWriteProblem): a run that will write the scene checks before it starts.
void requireWritableDensityGrids(const Scene& scene);

}  // namespace vkdr
