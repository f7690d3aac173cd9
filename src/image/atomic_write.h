#pragma once
#include <filesystem>
#include <functional>
#include <fstream>

namespace vkdr {

// Writes a file so that it is either complete or untouched: writeContents fills a
// temporary file beside `file`, which is then renamed over it. On any failure the
// temporary is removed and vkdr::Error names `file` (not the temporary). Refuses a
// `file` that exists and is not a regular file (a directory, device, FIFO, socket or
// symbolic link), which the rename would replace.
void writeAtomically(const std::filesystem::path& file, const std::function<void(std::ofstream&)>& writeContents);

// Removes the temporary files that writeAtomically left in `directory` when its process
// was killed mid-write (those of processes still running are left alone), so that a
// directory a run writes into again holds no partial file. Returns how many it removed.
size_t removeStaleTemporaries(const std::filesystem::path& directory);

}  // namespace vkdr
