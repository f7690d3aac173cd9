#include "image/encoded_image_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <zlib.h>

#include "image/image_formats.h"

namespace vkdr {

namespace {

const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
const unsigned char kJpegStart[3] = {0xff, 0xd8, 0xff};  // start of image, then a marker

// The Huffman tables of one DHT segment: a class and id byte, 16 code counts, the codes.
std::string huffmanTableProblem(const unsigned char* segment, size_t length, size_t offset) {
    size_t position = 0;
    while (position < length) {
        if (length - position < 17) return "a Huffman table at byte " + std::to_string(offset) + " is cut short";
        size_t codes = 0;
        for (size_t i = 1; i <= 16; ++i) codes += segment[position + i];
        if (codes > 256) {
            return "a Huffman table at byte " + std::to_string(offset) + " declares " + std::to_string(codes) +
                   " codes; at most 256 exist";
        }
        position += 17 + codes;
    }
    return {};
}

bool startsWith(const unsigned char* bytes, size_t size, const unsigned char* prefix, size_t length) {
    return size >= length && std::memcmp(bytes, prefix, length) == 0;
}

// The bit depths the PNG specification allows a colour type (its table 11.1), as a set of
// bits 1 << depth; 0 for a colour type it does not define. Debian's stb_image decodes some
// others (a 1-bit RGB image) as if they were allowed.
uint32_t allowedPngBitDepths(unsigned colourType) {
    switch (colourType) {
        case 0: return 1u << 1 | 1u << 2 | 1u << 4 | 1u << 8 | 1u << 16;  // grey
        case 3: return 1u << 1 | 1u << 2 | 1u << 4 | 1u << 8;             // palette
        case 2:                                                            // RGB
        case 4:                                                            // grey and alpha
        case 6: return 1u << 8 | 1u << 16;                                 // RGBA
        default: return 0;
    }
}

uint32_t bigEndian32(const unsigned char* bytes) {
    return uint32_t(bytes[0]) << 24 | uint32_t(bytes[1]) << 16 | uint32_t(bytes[2]) << 8 | uint32_t(bytes[3]);
}

std::string pngHeaderProblem(const unsigned char* data, uint32_t length) {
    if (length != 13) return "the PNG header chunk holds " + std::to_string(length) + " bytes, not 13";
    if (std::string problem = imageSizeProblem(bigEndian32(data), bigEndian32(data + 4)); !problem.empty()) {
        return problem;
    }
    const unsigned bitDepth = data[8], colourType = data[9];
    const uint32_t allowed = allowedPngBitDepths(colourType);
    if (allowed == 0) return "the PNG colour type " + std::to_string(colourType) + " is not one PNG defines";
    if (bitDepth > 16 || (allowed & (1u << bitDepth)) == 0) {
        std::string list;
        for (unsigned depth = 1; depth <= 16; ++depth) {
            if (allowed & (1u << depth)) list += (list.empty() ? "" : ", ") + std::to_string(depth);
        }
        return "the PNG colour type " + std::to_string(colourType) + " has bit depth " + std::to_string(bitDepth) +
               "; PNG allows it " + list;
    }
    return {};
}

}  // namespace

std::string imageSizeProblem(uint64_t width, uint64_t height) {
    if (width == 0 || height == 0) {
        return "the image is empty (" + std::to_string(width) + " x " + std::to_string(height) + " pixels)";
    }
    if (width > kMaxImagePixels || height > kMaxImagePixels || width * height > kMaxImagePixels) {
        return std::to_string(width) + " x " + std::to_string(height) + " pixels is too large";
    }
    return {};
}

bool isPngOrJpeg(const unsigned char* bytes, size_t size) {
    return startsWith(bytes, size, kPngSignature, sizeof(kPngSignature)) ||
           startsWith(bytes, size, kJpegStart, sizeof(kJpegStart));
}

std::string pngChunkProblem(const unsigned char* bytes, size_t size) {
    if (!startsWith(bytes, size, kPngSignature, sizeof(kPngSignature))) return {};
    // Each chunk: a big-endian 32-bit data length, a 4-byte type, the data, a 4-byte CRC.
    size_t offset = sizeof(kPngSignature);
    while (size - offset >= 8) {
        const uint32_t length = bigEndian32(bytes + offset);
        std::string type(reinterpret_cast<const char*>(bytes + offset + 4), 4);
        size_t left = size - offset - 8;
        if (length > left) {
            return "the PNG chunk '" + type + "' at byte " + std::to_string(offset) + " declares " +
                   std::to_string(length) + " bytes, but " + std::to_string(left) + " follow";
        }
        if (type == "IHDR") {
            if (std::string problem = pngHeaderProblem(bytes + offset + 8, length); !problem.empty()) return problem;
        }
        // stb_image checks no CRC: damaged pixel data would decode to wrong pixels without a
        // word. A critical chunk's CRC must match, as libpng requires by default.
        const bool critical = type[0] >= 'A' && type[0] <= 'Z';
        if (critical && left - length >= 4 &&
            crc32(0, bytes + offset + 4, uInt(4 + length)) != bigEndian32(bytes + offset + 8 + length)) {
            return "the PNG chunk '" + type + "' at byte " + std::to_string(offset) +
                   " is damaged (its CRC does not match its bytes)";
        }
        if (type == "IEND") return {};
        offset += 8 + size_t(length) + std::min<size_t>(4, left - length);  // a cut-off CRC ends the walk
    }
    return {};
}

std::string jpegProblem(const unsigned char* bytes, size_t size) {
    if (!startsWith(bytes, size, kJpegStart, sizeof(kJpegStart))) return {};
    size_t offset = 2;
    while (offset < size) {
        if (bytes[offset] != 0xff) return {};  // not a marker: left to the decoder to refuse
        while (offset < size && bytes[offset] == 0xff) ++offset;  // fill bytes before a marker
        if (offset >= size) return {};
        unsigned char marker = bytes[offset++];
        bool standalone = marker == 0x01 || (marker >= 0xd0 && marker <= 0xd9);  // TEM, RSTn, SOI, EOI
        if (standalone) continue;
        if (size - offset < 2) return "a JPEG marker segment at byte " + std::to_string(offset) + " is cut short";
        size_t length = size_t(bytes[offset]) << 8 | bytes[offset + 1];  // including these two bytes
        if (length < 2 || length > size - offset) {
            return "a JPEG marker segment at byte " + std::to_string(offset) + " declares " +
                   std::to_string(length) + " bytes, but " + std::to_string(size - offset) + " follow";
        }
        if (marker == 0xc4) {
            if (std::string problem = huffmanTableProblem(bytes + offset + 2, length - 2, offset); !problem.empty()) {
                return problem;
            }
        }
        // A start of frame (SOF0 to SOF15 but for DHT, JPG and DAC): precision, then the
        // height and width.
        const bool startOfFrame = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (startOfFrame && length >= 7) {
            const uint32_t height = uint32_t(bytes[offset + 3]) << 8 | bytes[offset + 4];
            const uint32_t width = uint32_t(bytes[offset + 5]) << 8 | bytes[offset + 6];
            // A height of 0 is left to a DNL marker after the first scan, which stb_image
            // does not read.
            if (height == 0 && width > 0) {
                return "the JPEG frame header leaves its height to a DNL marker, which is not read";
            }
            if (std::string problem = imageSizeProblem(width, height); !problem.empty()) return problem;
        }
        if (marker == 0xda) return {};  // start of scan: entropy-coded data follows
        offset += length;
    }
    return {};
}

}  // namespace vkdr
