#include <algorithm>
#include <cctype>
#include <string>

#include "core/error.h"
#include "image/image.h"
#include "image/image_formats.h"
#include "image/regular_file.h"

namespace vkdr {

std::string lowercaseExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

Image readImage(const std::filesystem::path& file) {
    std::string reason = notRegularFileReason(file);
    if (!reason.empty()) throw Error("cannot read image '" + file.string() + "': " + reason);

    const std::string extension = lowercaseExtension(file);
    if (extension == ".exr") return readExr(file);
    if (extension == ".png" || extension == ".jpg" || extension == ".jpeg") return readPngOrJpeg(file);
    throw Error("cannot read image '" + file.string() + "': unknown extension '" + extension +
                "' (expected .exr, .png, .jpg or .jpeg)");
}

}  // namespace vkdr
