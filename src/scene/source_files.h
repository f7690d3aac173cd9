#pragma once
#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

namespace vkdr {

// A file a scene was loaded from, by a digest of its bytes as they were read.
struct SourceFile {
    std::filesystem::path file;  // symbolic links resolved
    size_t digest = 0;
};

// The digest SourceFile keeps: a hash of the bytes, for telling within one process
// whether a file still holds what was loaded from it.
size_t contentDigest(std::string_view bytes);

// Throws vkdr::Error naming `file` when `sources` lists it (after resolving symbolic
// links) with other bytes than `bytes`: writing a scene back from a changed original
// would mix the file's new contents with values that belong to the old ones.
void requireUnchangedSource(const std::vector<SourceFile>& sources, const std::filesystem::path& file,
                            std::string_view bytes);

}  // namespace vkdr
