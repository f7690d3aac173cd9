#pragma once
#include <filesystem>

#include "image/image.h"

namespace vkdr {

// The readers behind readImage, one per file format. Each throws vkdr::Error naming
// the file when it cannot read it.
Image readExr(const std::filesystem::path& file);
Image readPngOrJpeg(const std::filesystem::path& file);

// Larger images are refused rather than allocated: a corrupt header must not make
// a reader try to claim all memory.
inline constexpr size_t kMaxImagePixels = size_t(1) << 28;

}  // namespace vkdr
