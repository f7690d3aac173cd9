#pragma once
#include <filesystem>
#include <functional>
#include <fstream>
#include <utility>
#include <vector>

#include "core/interrupt.h"

namespace vkdr {

// Files written together (an image and its preview): writeAtomically leaves each one's
// temporary here, complete, and commit() renames them all into place, so that a write
// that fails leaves every file as it was. Destroyed before commit(), it removes the
// temporaries. While it lives, a second signal waits (FileWriteGuard).
class PendingRenames {
public:
    PendingRenames() = default;
    PendingRenames(const PendingRenames&) = delete;
    PendingRenames& operator=(const PendingRenames&) = delete;
    ~PendingRenames();
    // Throws vkdr::Error naming the file whose rename failed.
    void commit();

private:
    friend void writeAtomically(const std::filesystem::path&, const std::function<void(std::ofstream&)>&,
                                PendingRenames*);
    FileWriteGuard writing_;
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> renames_;  // temporary, file
};

// Writes a file so that it is either complete or untouched: writeContents fills a
// temporary file beside `file`, which is then renamed over it (by pending->commit() where
// `pending` is given). On any failure the temporary is removed and vkdr::Error names
// `file` (not the temporary). Refuses a `file` that exists and is not a regular file (a
// directory, device, FIFO, socket or symbolic link), which the rename would replace.
void writeAtomically(const std::filesystem::path& file, const std::function<void(std::ofstream&)>& writeContents,
                     PendingRenames* pending = nullptr);

// Removes the temporary files that writeAtomically left in `directory` when its process
// was killed mid-write (those of processes still running are left alone), so that a
// directory a run writes into again holds no partial file. Returns how many it removed.
size_t removeStaleTemporaries(const std::filesystem::path& directory);

}  // namespace vkdr
