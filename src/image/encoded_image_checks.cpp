#include "image/encoded_image_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace vkdr {

namespace {

const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

bool startsWith(const unsigned char* bytes, size_t size, const unsigned char* prefix, size_t length) {
    return size >= length && std::memcmp(bytes, prefix, length) == 0;
}

}  // namespace

bool isPngOrJpeg(const unsigned char* bytes, size_t size) {
    static const unsigned char kJpegStart[3] = {0xff, 0xd8, 0xff};  // start of image, then a marker
    return startsWith(bytes, size, kPngSignature, sizeof(kPngSignature)) ||
           startsWith(bytes, size, kJpegStart, sizeof(kJpegStart));
}

std::string pngChunkProblem(const unsigned char* bytes, size_t size) {
    if (!startsWith(bytes, size, kPngSignature, sizeof(kPngSignature))) return {};
    // Each chunk: a big-endian 32-bit data length, a 4-byte type, the data, a 4-byte CRC.
    size_t offset = sizeof(kPngSignature);
    while (size - offset >= 8) {
        uint32_t length = uint32_t(bytes[offset]) << 24 | uint32_t(bytes[offset + 1]) << 16 |
                          uint32_t(bytes[offset + 2]) << 8 | uint32_t(bytes[offset + 3]);
        std::string type(reinterpret_cast<const char*>(bytes + offset + 4), 4);
        size_t left = size - offset - 8;
        if (length > left) {
            return "the PNG chunk '" + type + "' at byte " + std::to_string(offset) + " declares " +
                   std::to_string(length) + " bytes, but " + std::to_string(left) + " follow";
        }
        if (type == "IEND") return {};
        offset += 8 + size_t(length) + std::min<size_t>(4, left - length);  // a cut-off CRC ends the walk
    }
    return {};
}

}  // namespace vkdr
