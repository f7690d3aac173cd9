#include "volume/nanovdb_file_layout.h"

#include <fstream>
#include <string>

#include <nanovdb/util/IO.h>

#include "core/error.h"
#include "core/format_text.h"

namespace vkdr {
namespace {

constexpr uint64_t kLargestCompressionRatio = 1100;

[[noreturn]] void failDamaged(const std::string& what) {
    throw Error("the file is damaged (" + what + ")");
}

}  // namespace

void requireSoundNanoVdbLayout(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const uint64_t size = std::filesystem::file_size(file);
    uint64_t at = 0;
    auto read = [&](void* into, uint64_t bytes, const char* what) {
        if (size - at < bytes) {
            failDamaged(formatText("it ends inside %s, at byte %llu of %llu: it is truncated", what,
                                   (unsigned long long)at, (unsigned long long)size));
        }
        in.read(static_cast<char*>(into), std::streamsize(bytes));
        if (!in) throw Error(formatText("cannot read %s at byte %llu", what, (unsigned long long)at));
        at += bytes;
    };
    size_t grid = 0;
    while (at < size) {
        nanovdb::io::Header header;
        read(&header, sizeof(header), "a segment's header");
        if (header.magic != NANOVDB_MAGIC_NUMBER) return;
        uint64_t gridBytes = 0;  // the segment's grids follow all of its descriptions
        for (uint16_t i = 0; i < header.gridCount; ++i, ++grid) {
            nanovdb::io::MetaData meta;
            read(&meta, sizeof(meta), "a grid's description");
            if (meta.nameSize == 0 || meta.nameSize > size - at) {
                failDamaged(formatText("grid %zu's name takes %u bytes, where %llu are left", grid, meta.nameSize,
                                       (unsigned long long)(size - at)));
            }
            std::string name(meta.nameSize, '\0');
            read(name.data(), meta.nameSize, "a grid's name");
            if (name.back() != '\0') failDamaged(formatText("grid %zu's name is not terminated", grid));
            gridBytes += meta.fileSize;
            if (meta.fileSize > size - at || gridBytes > size - at) {
                failDamaged(formatText("grid %zu takes %llu bytes on disk, beyond the file's %llu", grid,
                                       (unsigned long long)meta.fileSize, (unsigned long long)size));
            }
            const bool compressed = header.codec != nanovdb::io::Codec::NONE;
            const bool fits = compressed ? meta.gridSize / kLargestCompressionRatio <= meta.fileSize
                                         : meta.gridSize == meta.fileSize;
            if (!fits) {
                failDamaged(formatText("grid %zu takes %llu bytes in memory from %llu on disk%s", grid,
                                       (unsigned long long)meta.gridSize, (unsigned long long)meta.fileSize,
                                       compressed ? ", more than any compression gives" : ", uncompressed"));
            }
        }
        in.seekg(std::streamoff(gridBytes), std::ios::cur);
        at += gridBytes;
    }
}

}  // namespace vkdr
