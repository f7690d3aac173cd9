#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace vkdr {

// Checks on encoded bytes before stb_image decodes them.

// Whether the bytes start as a PNG or a JPEG file does. stb_image also reads TGA, PSD,
// PNM and others by their content, and some of those decode a header of a few bytes into
// a huge image of zeros; targets may only be PNG or JPEG (or EXR), so the rest are refused.
bool isPngOrJpeg(const unsigned char* bytes, size_t size);

// What is wrong with an image of width x height pixels: no pixels, or more than
// kMaxImagePixels (empty when nothing is). The decoder refuses such an image with a reason
// that its callers lose (they go on trying other formats), so the header's size is
// checked first, and the decoder's again after it.
std::string imageSizeProblem(uint64_t width, uint64_t height);

// For bytes that start with the PNG signature: what is wrong when a chunk declares more
// bytes than follow it, a critical chunk's CRC does not match its bytes, or the header
// gives no pixels, more than kMaxImagePixels, or a
// colour type and bit depth PNG does not allow (empty when none, or the bytes are not a
// PNG).
// stb_image sizes its buffer for the compressed data by the declared lengths before
// reading them, so a few corrupt bytes could make it claim gigabytes; callers check this
// first.
std::string pngChunkProblem(const unsigned char* bytes, size_t size);

// For bytes that start as a JPEG: what is wrong when a marker segment before the scan
// data is longer than the file, a Huffman table declares more than 256 codes, or the
// frame header gives no pixels or more than kMaxImagePixels (empty when none, or the
// bytes are not a JPEG). Debian's stb_image writes past its
// Huffman arrays for such a table (found by tools/fuzz.sh), so callers check this first.
std::string jpegProblem(const unsigned char* bytes, size_t size);

}  // namespace vkdr
