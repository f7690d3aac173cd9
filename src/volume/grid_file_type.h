#pragma once
#include <filesystem>
#include <optional>

namespace vkdr {

enum class GridFileType { Vdb, NanoVdb };

// The type a density grid file has by its extension: ".vdb" (OpenVDB) or ".nvdb"
// (NanoVDB), in any case; nullopt for any other.
std::optional<GridFileType> gridFileTypeOf(const std::filesystem::path& file);

}  // namespace vkdr
