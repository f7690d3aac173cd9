#pragma once
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace vkdr {

// The most voxels a dense grid may hold: every flat index fits a 32-bit signed integer.
constexpr uint64_t kMaxDenseVoxels = (uint64_t(1) << 31) - 1;

// Why `indexToLocal` cannot serve as a grid's index-to-local transform: "" when it can.
// It must be finite and affine (last row 0 0 0 1), and no voxel may be flattened: the
// volume of the voxel's parallelepiped is at least 1e-6 of the product of its edge
// lengths (edges more than about 1e-4 degrees from coplanar).
std::string indexTransformProblem(const glm::dmat4& indexToLocal);

}  // namespace vkdr
