#pragma once
// For vkdr_volume's own .cpp files only: it brings in OpenVDB, which the library's
// public headers keep out.
#include <string>

#include <openvdb/openvdb.h>

#include <glm/glm.hpp>

namespace vkdr {

// openvdb::initialize(), once per process, safe to call from any thread.
void initializeOpenVdb();

// OpenVDB maps row vectors (index * M, translation in row 3); glm maps column vectors
// (M * index, translation in column 3): the same numbers at the same [i][j].
glm::dmat4 toGlm(const openvdb::math::Mat4d& matrix);
openvdb::math::Mat4d toOpenVdb(const glm::dmat4& matrix);

// A transform holding `indexToLocal` exactly, as an AffineMap. (Transform's constructor
// would "simplify" a scale-and-translate matrix, recomputing the scale from differences
// of mapped points, which loses bits, and merging scales within 1e-7 of each other.)
openvdb::math::Transform::Ptr exactTransform(const glm::dmat4& indexToLocal);

// Why OpenVDB cannot hold `indexToLocal` (finite and affine) as a map: "" when it can.
// Its maps refuse voxels of a volume (determinant) under 3e-15, about 1.44e-5 a side,
// however well shaped.
std::string openVdbMapProblem(const glm::dmat4& indexToLocal);

}  // namespace vkdr
