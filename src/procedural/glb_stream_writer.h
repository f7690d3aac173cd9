#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace vkdr {

// Writes a binary glTF (.glb: header, JSON chunk, BIN chunk) without holding the binary
// data in memory. The JSON usually depends on the data (accessor bounds), so its chunk
// is reserved up front and written last, padded with spaces as GLB allows.
class GlbStreamWriter {
public:
    // `jsonCapacity`: the most JSON bytes finish() may write; `binaryBytes`: exactly
    // how many bytes writeBinary() will receive in total.
    GlbStreamWriter(const std::filesystem::path& file, size_t jsonCapacity, uint64_t binaryBytes);
    ~GlbStreamWriter();
    GlbStreamWriter(const GlbStreamWriter&) = delete;
    GlbStreamWriter& operator=(const GlbStreamWriter&) = delete;

    void writeBinary(const void* data, size_t bytes);
    void finish(const std::string& json);

private:
    void write(const void* data, size_t bytes);

    std::filesystem::path path_;
    std::FILE* file_ = nullptr;
    uint32_t jsonChunkBytes_ = 0;  // reserved, a multiple of 4
    uint64_t binaryBytes_ = 0;
    uint64_t binaryWritten_ = 0;
};

}  // namespace vkdr
