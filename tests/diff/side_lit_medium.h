#pragma once
// Pieces of the scenes the voxel-gradient tests share: a medium's box x, y in
// [-0.6, 0.6], z in [1, 2.2], in front of the camera, and a square emitter beside it.
#include "test_gltf.h"
#include "volume/density_grid.h"

namespace vkdr::test {

// A grid named "density" of voxels^3 voxels whose centres span the medium's box, with
// no values yet.
DensityGrid gridOverMediumBox(int voxels);

// A square emitter of half-size 0.4 in the plane x = 1.5, centred at (1.5, 0, 1.6) and
// facing -x, towards the medium.
TestMesh sideEmitter(int material);

}  // namespace vkdr::test
