#pragma once
// Density grids and OpenVDB files made by hand, for the volume tests.
#include <filesystem>
#include <string>

#include <openvdb/openvdb.h>

#include "volume/density_grid.h"

namespace vkdr::test {

// A general affine index-to-local transform: rotated, scaled differently along each
// axis and translated.
glm::dmat4 skewedTransform();

// A grid over `size` voxels from `first` whose values are all non-zero on the box's
// faces (so that its active box is the whole box) and, where the box has an inside, an
// exact zero at its centre.
DensityGrid patternedGrid(glm::ivec3 first, glm::ivec3 size, const glm::dmat4& indexToLocal);

// Writes `grid` to a .vdb file with OpenVDB itself.
void writeOpenVdbGrid(const std::filesystem::path& file, const openvdb::GridBase::Ptr& grid);

// A float grid named `name` with the voxels of `grid` (non-zero ones active).
openvdb::FloatGrid::Ptr openVdbGrid(const DensityGrid& grid);

// The bytes of `file`.
std::string fileBytes(const std::filesystem::path& file);

}  // namespace vkdr::test
