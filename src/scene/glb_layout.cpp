#include "scene/glb_layout.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace vkdr {
namespace {

constexpr uint32_t kMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinaryChunk = 0x004E4942;

uint32_t readUint32(std::string_view bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof(value));  // GLB is little-endian, as is every target
    return value;
}

// "BIN", "JSON", or the four bytes in hex when they are not all printable.
std::string chunkTypeName(uint32_t type) {
    std::string name;
    for (int i = 0; i < 4; ++i) {
        char c = char((type >> (8 * i)) & 0xFF);
        if (c == '\0' && i == 3) break;
        if (!std::isprint(static_cast<unsigned char>(c))) {
            char hex[16];
            std::snprintf(hex, sizeof(hex), "0x%08X", type);
            return hex;
        }
        name += c;
    }
    return name;
}

}  // namespace

GlbLayout glbLayout(std::string_view bytes) {
    GlbLayout layout;
    if (bytes.size() < 12 || readUint32(bytes, 0) != kMagic) {
        layout.problem = "not a GLB file (no 12-byte header starting with 'glTF')";
        return layout;
    }
    if (uint32_t version = readUint32(bytes, 4); version != 2) {
        layout.problem = "GLB version " + std::to_string(version) + "; only version 2 is read";
        return layout;
    }
    size_t length = readUint32(bytes, 8);
    if (length > bytes.size()) {
        layout.problem = "the GLB header declares " + std::to_string(length) + " bytes; the file has " +
                         std::to_string(bytes.size());
        return layout;
    }
    if (length < bytes.size()) {
        layout.ignored.push_back(std::to_string(bytes.size() - length) +
                                 " bytes after the length the GLB header declares are ignored");
    }
    size_t index = 0;
    for (size_t offset = 12; offset < length; ++index) {
        std::string chunk = "GLB chunk " + std::to_string(index);
        if (offset + 8 > length) {
            layout.problem = chunk + " header runs past the end of the file";
            return layout;
        }
        size_t chunkLength = readUint32(bytes, offset);
        uint32_t type = readUint32(bytes, offset + 4);
        if (chunkLength > length - offset - 8) {
            layout.problem = chunk + " runs past the end of the file";
            return layout;
        }
        std::string_view data = bytes.substr(offset + 8, chunkLength);
        if (index == 0 && type != kJsonChunk) {
            layout.problem = chunk + " is " + chunkTypeName(type) + "; the first chunk must be JSON";
            return layout;
        }
        if (index == 0) {
            layout.json = data;
        } else if (index == 1 && type == kBinaryChunk) {
            layout.binary = data;
        } else if (index == 1) {
            layout.problem = chunk + " is " + chunkTypeName(type) + "; the chunk after the JSON must be BIN";
            return layout;
        } else {
            layout.ignored.push_back(chunk + " (" + chunkTypeName(type) + ", " + std::to_string(chunkLength) +
                                     " bytes) is ignored: only the first BIN chunk, buffers[0], is read");
        }
        offset += 8 + chunkLength;
    }
    if (index == 0) layout.problem = "a GLB file without a JSON chunk";
    return layout;
}

}  // namespace vkdr
