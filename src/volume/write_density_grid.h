#pragma once
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "volume/density_grid.h"

namespace vkdr {

// Writes `grid` as an OpenVDB FloatGrid of class fog volume (a Vec3SGrid of no class for
// 3 channels) named grid.name ("density" when empty), background 0, its non-zero voxels and the two extreme corners of its box
// active, with indexToLocal as an affine
// map: readDensityGrid (readAlbedoGrid) gives back the same box, values and matrix bit for bit. The file
// is written atomically (complete or untouched). Throws vkdr::Error for a grid whose
// values do not match its size, a negative or non-finite value, or a transform that
// gridTransformWriteProblem refuses.
void writeDensityGridVdb(const std::filesystem::path& file, const DensityGrid& grid);

// The same grid as a NanoVDB (.nvdb) file, uncompressed; read back bit for bit as well.
void writeDensityGridNanoVdb(const std::filesystem::path& file, const DensityGrid& grid);

// Why a grid with `indexToLocal` cannot be written (either format goes through
// OpenVDB's transforms): indexTransformProblem's reasons, or voxels smaller than
// OpenVDB's maps hold (openVdbMapProblem); "" when it can.
std::string gridTransformWriteProblem(const glm::dmat4& indexToLocal);

// One of the two by the file's extension (gridFileTypeOf); vkdr::Error for any other.
void writeDensityGrid(const std::filesystem::path& file, const DensityGrid& grid);

}  // namespace vkdr
