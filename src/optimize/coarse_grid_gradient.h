#pragma once
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

namespace vkdr {

// Coarse-to-fine fitting of a density grid. Early in a run the steps are restricted to
// grids that are trilinear interpolations of a coarser grid, whose voxels each gather
// the gradients of many fine ones: far less noisy, and with far fewer unknowns for the
// views to pin down. Later levels halve the coarse voxel until the grid's own.
//
// A coarse grid with `divisor` D has ceil(size / D) voxels per axis; coarse voxel c sits
// at fine index coordinate (c + 0.5) D - 0.5 (fine voxels at their integers), so that
// fine voxel i takes the trilinear interpolation of the coarse grid at (i + 0.5) / D -
// 0.5, clamped to its first and last voxel. This is the linear map U from coarse values
// to fine ones.

// U: `coarse` (the coarse grid's values, x fastest) to `fine` (size's values).
void prolongGrid(glm::ivec3 size, uint32_t divisor, std::span<const double> coarse, std::span<double> fine);

// U transposed: each fine value added into the coarse voxels it interpolates, with its
// weight. `coarse` is set, not added to.
void prolongGridTransposed(glm::ivec3 size, uint32_t divisor, std::span<const double> fine,
                           std::span<double> coarse);

// The coarse grid's voxels per axis.
glm::ivec3 coarseGridSize(glm::ivec3 size, uint32_t divisor);

// Replaces a fine grid's gradient g with U U^T g: the direction gradient descent on the
// coarse grid's values would move the fine grid in. With plain gradient descent from a
// grid that is such an interpolation (a constant start), the steps are exactly those of
// fitting the coarse grid; Adam scales each voxel's step by its own history, so it
// follows them closely but not exactly. A divisor of 1 leaves the gradient as it is.
void coarsenGridGradient(glm::ivec3 size, uint32_t divisor, std::span<double> gradient);

// Past this many levels the first would be more than 512 times coarser than the grid.
inline constexpr uint32_t kMostGridLevels = 10;

// The divisor at `iteration` of `iterations` with `levels` levels: the run split into
// `levels` equal parts, the first with divisor 2^(levels - 1), each next one half the
// last, the final one 1.
uint32_t gridDivisorAt(uint32_t iteration, uint32_t iterations, uint32_t levels);

}  // namespace vkdr
