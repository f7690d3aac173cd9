#include "volume/grid_file_type.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace vkdr {

std::optional<GridFileType> gridFileTypeOf(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".vdb") return GridFileType::Vdb;
    if (extension == ".nvdb") return GridFileType::NanoVdb;
    return std::nullopt;
}

}  // namespace vkdr
