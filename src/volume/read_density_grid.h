#pragma once
#include <filesystem>
#include <string>

#include "volume/density_grid.h"

namespace vkdr {

// Reads the scalar grid `gridName` from an OpenVDB (.vdb) or NanoVDB (.nvdb) file, by
// extension, into the dense box of its active voxels (tiles included); inactive voxels
// inside the box are 0. Float grids are read as they are and double grids rounded to
// float. A grid without active voxels gives size 0.
//
// Throws vkdr::Error naming the file for: a missing or unreadable file, one that is not
// a VDB/NanoVDB file, an unknown extension, no grid of that name (the error lists the
// names there are), a grid of any other value type (vectors, integers, masks), a
// negative or non-finite voxel, a transform that is not affine or is singular
// (indexTransformProblem), and a box of more than kMaxDenseVoxels voxels.
DensityGrid readDensityGrid(const std::filesystem::path& file, const std::string& gridName);

// The same for an emission grid (a scalar strength per voxel, refused and named as such).
DensityGrid readEmissionGrid(const std::filesystem::path& file, const std::string& gridName);

// The same for an albedo grid (channels 3): a vector grid (float or double; Vec3f in
// NanoVDB) gives each voxel its RGB, a scalar grid a grey one. Every channel must lie in
// [0, 1]; the other refusals are readDensityGrid's.
DensityGrid readAlbedoGrid(const std::filesystem::path& file, const std::string& gridName);

}  // namespace vkdr
