#pragma once
#include <cstdint>

#include "volume/density_grid.h"

namespace vkdr {

// A procedural smoke plume rising along +y (up, as in glTF) on resolution^3 voxels whose
// index box maps onto the cube [-0.5, 0.5]^3 in local space: voxel size 1/resolution,
// voxel (i, j, k) centred at ((i, j, k) + 0.5) / resolution - 0.5. Densities lie in
// [0, 1]; the outermost layer of voxels and everything within 0.05 of a face is exactly
// 0, as is most of the box around the plume. The same resolution and seed give the same
// values bit for bit; another seed gives another plume. Throws vkdr::Error for a
// resolution below 2 or one whose voxels a dense grid cannot hold (above 1290).
DensityGrid makeSmokePlume(int resolution, uint32_t seed);

// The flame of such a plume, a fire's emission strength (as the `flame` grid of Blender's
// fire simulations): the plume's density where it is hot, fading from the column's source
// to 0 some 0.45 higher. Same box and placement; values in [0, 1]; named "flame".
DensityGrid flameOfPlume(const DensityGrid& plume);

}  // namespace vkdr
