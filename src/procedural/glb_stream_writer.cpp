#include "procedural/glb_stream_writer.h"

#include <string>
#include <vector>

#include "core/error.h"

namespace vkdr {
namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinaryChunk = 0x004E4942;  // "BIN\0"
constexpr size_t kHeaderBytes = 12;
constexpr size_t kChunkHeaderBytes = 8;

uint64_t paddedToFour(uint64_t bytes) { return (bytes + 3) & ~uint64_t(3); }

}  // namespace

GlbStreamWriter::GlbStreamWriter(const std::filesystem::path& file, size_t jsonCapacity,
                                 uint64_t binaryBytes)
    : path_(file), jsonChunkBytes_(uint32_t(paddedToFour(jsonCapacity))), binaryBytes_(binaryBytes) {
    uint64_t total = kHeaderBytes + kChunkHeaderBytes + jsonChunkBytes_ + kChunkHeaderBytes +
                     paddedToFour(binaryBytes);
    if (total > UINT32_MAX) {
        throw Error(path_.string() + ": " + std::to_string(total) +
                    " bytes exceed the 4 GiB limit of a .glb file");
    }
    file_ = std::fopen(file.string().c_str(), "wb");
    if (!file_) {
        throw Error(path_.string() + ": cannot open for writing");
    }
    uint32_t header[3] = {kMagic, 2, uint32_t(total)};
    write(header, sizeof(header));
    // The JSON chunk is filled in by finish(); spaces keep it valid meanwhile.
    uint32_t jsonHeader[2] = {jsonChunkBytes_, kJsonChunk};
    write(jsonHeader, sizeof(jsonHeader));
    std::string blank(jsonChunkBytes_, ' ');
    write(blank.data(), blank.size());
    uint32_t binaryHeader[2] = {uint32_t(paddedToFour(binaryBytes)), kBinaryChunk};
    write(binaryHeader, sizeof(binaryHeader));
}

GlbStreamWriter::~GlbStreamWriter() {
    if (file_) {
        std::fclose(file_);
    }
}

void GlbStreamWriter::write(const void* data, size_t bytes) {
    // An empty vector's data() may be null, which fwrite must not be given even for 0 bytes.
    if (bytes == 0) {
        return;
    }
    if (std::fwrite(data, 1, bytes, file_) != bytes) {
        throw Error(path_.string() + ": write failed");
    }
}

void GlbStreamWriter::writeBinary(const void* data, size_t bytes) {
    write(data, bytes);
    binaryWritten_ += bytes;
}

void GlbStreamWriter::finish(const std::string& json) {
    if (binaryWritten_ != binaryBytes_ || json.size() > jsonChunkBytes_) {
        throw Error(path_.string() + ": internal error: chunk sizes differ from the reservation");
    }
    std::vector<char> padding(paddedToFour(binaryBytes_) - binaryBytes_, 0);
    write(padding.data(), padding.size());
    if (std::fseek(file_, long(kHeaderBytes + kChunkHeaderBytes), SEEK_SET) != 0) {
        throw Error(path_.string() + ": seek failed");
    }
    write(json.data(), json.size());
    if (std::fclose(file_) != 0) {
        file_ = nullptr;
        throw Error(path_.string() + ": write failed");
    }
    file_ = nullptr;
}

}  // namespace vkdr
