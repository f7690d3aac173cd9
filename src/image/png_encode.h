#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "image/image.h"

namespace vkdr {

// PNG files in memory, for pages that embed their images (data: URIs).

// `image` as writePng writes it: sRGB-encoded, clamped to [0, 1], 8 bits per channel.
std::vector<unsigned char> encodePng(const Image& image);

// 8-bit RGB samples already in display encoding (width * height * 3, row 0 at the top),
// written as they are: for false-colour images whose colours are chosen, not measured.
std::vector<unsigned char> encodePngRgb8(int width, int height, std::span<const uint8_t> rgb);

}  // namespace vkdr
