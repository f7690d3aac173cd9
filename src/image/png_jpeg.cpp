#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/error.h"
#include "image/atomic_write.h"
#include "image/image_formats.h"
#include "image/png_encode.h"
#include "image/encoded_image_checks.h"
#include "image/srgb.h"

namespace vkdr {
namespace {

// stb_image's reason for its last failure, which is terse (a file cut inside a chunk's
// name gives that name cut short, "IDA"), or none at all for some data cut short.
std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason && *reason ? std::string("damaged, cut short or of a kind not read (the decoder says: ") + reason + ")"
                             : "damaged or cut short";
}

[[noreturn]] void failToRead(const std::filesystem::path& file, const std::string& reason) {
    throw Error("cannot read image '" + file.string() + "': " + reason);
}

std::vector<unsigned char> readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) failToRead(file, "cannot open it");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) failToRead(file, "read error");
    return bytes;
}

// Decodes sRGB-encoded samples of a given bit depth to linear RGB; grey is
// replicated and alpha is dropped.
template <typename Sample>
Image decode(const Sample* samples, int width, int height, int channels, float maxValue) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.resize(size_t(width) * height * 3);
    bool grey = channels < 3;
    for (size_t p = 0; p < size_t(width) * height; ++p)
        for (int c = 0; c < 3; ++c)
            image.rgb[3 * p + c] = linearFromSrgb(float(samples[p * channels + (grey ? 0 : c)]) / maxValue);
    return image;
}

struct StbFree {
    void operator()(void* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

std::vector<unsigned char> encodePngRgb8(int width, int height, std::span<const uint8_t> rgb) {
    if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * height * 3)
        throw Error("cannot encode PNG: the image has no pixels or the wrong number of values");
    std::vector<unsigned char> png;
    auto append = [](void* out, void* data, int size) {
        auto* bytes = static_cast<const unsigned char*>(data);
        auto* encoded = static_cast<std::vector<unsigned char>*>(out);
        encoded->insert(encoded->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
        throw Error("cannot encode PNG: encoding failed");
    return png;
}

std::vector<unsigned char> encodePng(const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        throw Error("cannot encode PNG: the image has no pixels or the wrong number of values");
    std::vector<uint8_t> encoded(image.rgb.size());
    for (size_t i = 0; i < encoded.size(); ++i)
        encoded[i] = static_cast<uint8_t>(std::lround(255.0f * srgbFromLinear(image.rgb[i])));
    return encodePngRgb8(image.width, image.height, encoded);
}

void writePng(const std::filesystem::path& file, const Image& image, PendingRenames* pending) {
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        throw Error("cannot write PNG '" + file.string() + "': the image has no pixels or the wrong number of values");
    std::vector<unsigned char> png = encodePng(image);
    writeAtomically(file, [&](std::ofstream& out) {
        out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    }, pending);
}

Image readPngOrJpeg(const std::filesystem::path& file) {
    std::vector<unsigned char> bytes = readBytes(file);
    if (bytes.empty()) failToRead(file, "the file is empty");
    if (bytes.size() > size_t(INT_MAX)) failToRead(file, "the file is too large");
    int length = int(bytes.size());
    if (!isPngOrJpeg(bytes.data(), bytes.size())) failToRead(file, "not a PNG or JPEG file (by its first bytes)");
    if (std::string problem = pngChunkProblem(bytes.data(), bytes.size()); !problem.empty()) failToRead(file, problem);
    if (std::string problem = jpegProblem(bytes.data(), bytes.size()); !problem.empty()) failToRead(file, problem);

    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
        failToRead(file, "not a PNG or JPEG image we can decode (" + stbReason() + ")");
    if (std::string problem = imageSizeProblem(uint64_t(std::max(width, 0)), uint64_t(std::max(height, 0)));
        !problem.empty()) {
        failToRead(file, problem);
    }

    if (stbi_is_16_bit_from_memory(bytes.data(), length)) {
        std::unique_ptr<stbi_us, StbFree> pixels(stbi_load_16_from_memory(bytes.data(), length, &width, &height, &channels, 0));
        if (!pixels) failToRead(file, stbReason());
        return decode(pixels.get(), width, height, channels, 65535.0f);
    }
    std::unique_ptr<stbi_uc, StbFree> pixels(stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 0));
    if (!pixels) failToRead(file, stbReason());
    return decode(pixels.get(), width, height, channels, 255.0f);
}

}  // namespace vkdr
