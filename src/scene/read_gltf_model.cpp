#include "scene/read_gltf_model.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>

#include <stb_image.h>

#include "image/encoded_image_checks.h"

namespace vkdr {
namespace {

std::string lowercaseExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

// tinygltf ends most messages with a newline; one-line messages read better.
std::string trimmed(std::string text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
        text.pop_back();
    }
    return text;
}

// Textures become RGBA float texels (16 bytes each); 8192 x 8192 is the largest allowed.
constexpr int64_t kMaxTextureTexels = int64_t(1) << 26;

// tinygltf's own image decoder, after a look at the image's header: a corrupt or hostile
// file that declares an enormous image is refused before any pixel memory is claimed.
bool loadBoundedImage(tinygltf::Image* image, const int imageIndex, std::string* error, std::string* warning,
                      int width, int height, const unsigned char* bytes, int size, void*) {
    std::string problem = pngChunkProblem(bytes, size_t(size));
    if (problem.empty()) problem = jpegProblem(bytes, size_t(size));
    if (!problem.empty()) {
        *error += "images[" + std::to_string(imageIndex) + "] cannot be decoded: " + problem + "\n";
        return false;
    }
    int declaredWidth = 0, declaredHeight = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, size, &declaredWidth, &declaredHeight, &channels)) {
        // stb_image tries every format it knows, so its own reason names only the last.
        *error += "images[" + std::to_string(imageIndex) +
                  "] cannot be decoded: it is damaged, of a type stb_image does not read, or over 1 GiB decoded\n";
        return false;
    }
    if (int64_t(declaredWidth) * int64_t(declaredHeight) > kMaxTextureTexels) {
        *error += "images[" + std::to_string(imageIndex) + "] is " + std::to_string(declaredWidth) + " x " +
                  std::to_string(declaredHeight) + " texels; at most " + std::to_string(kMaxTextureTexels) +
                  " (8192 x 8192) are read\n";
        return false;
    }
    // No options: tinygltf's default, every image decoded to 4 channels.
    return tinygltf::LoadImageData(image, imageIndex, error, warning, width, height, bytes, size, nullptr);
}

}  // namespace

tinygltf::Model readGltfModel(const std::filesystem::path& file, GltfDiagnostics& diagnostics) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        diagnostics.fail("", "no such file");
    }
    std::string extension = lowercaseExtension(file);
    if (extension != ".gltf" && extension != ".glb") {
        diagnostics.fail("", "expected a .gltf or .glb file");
    }

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(loadBoundedImage, nullptr);
    tinygltf::Model model;
    std::string error;
    std::string warning;
    bool loaded = extension == ".glb"
                      ? loader.LoadBinaryFromFile(&model, &error, &warning, file.string())
                      : loader.LoadASCIIFromFile(&model, &error, &warning, file.string());
    if (!loaded) {
        diagnostics.fail("", "cannot parse glTF: " +
                                 trimmed(error.empty() ? warning : error));
    }
    if (!trimmed(warning).empty()) {
        diagnostics.warn("", trimmed(warning));
    }
    return model;
}

}  // namespace vkdr
