#pragma once
#include <filesystem>
#include <functional>
#include <fstream>

namespace vkdr {

// Writes a file so that it is either complete or untouched: writeContents fills a
// temporary file beside `file`, which is then renamed over it. On any failure the
// temporary is removed and vkdr::Error names `file` (not the temporary).
void writeAtomically(const std::filesystem::path& file, const std::function<void(std::ofstream&)>& writeContents);

}  // namespace vkdr
