#include "scene/read_gltf_model.h"

#include <algorithm>
#include <cctype>

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
