#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vkdr {

// Linear RGB, 32-bit float, row 0 at the top of the image.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // width * height * 3
    float* pixel(int x, int y) { return &rgb[(size_t(y) * width + x) * 3]; }
    const float* pixel(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};

class PendingRenames;

// Writers never leave a partial file behind: they write a temporary file beside the
// destination and rename it over the destination only when complete (with `pending`,
// when pending->commit() renames the files written together; image/atomic_write.h).
void writeExr(const std::filesystem::path& file, const Image& image, PendingRenames* pending = nullptr);
// Preview: sRGB-encoded, clamped to [0, 1], 8 bits per channel.
void writePng(const std::filesystem::path& file, const Image& image, PendingRenames* pending = nullptr);

// Reads an EXR (R, G, B channels; Y alone is grey) or a PNG/JPEG (sRGB decoded to
// linear). Throws vkdr::Error naming the file on anything it cannot read.
Image readImage(const std::filesystem::path& file);

// The file's extension in lower case (".exr"), by which readImage picks its reader.
std::string lowercaseExtension(const std::filesystem::path& file);

}  // namespace vkdr
