#include "scene/read_gltf_model.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "core/error.h"
#include "image/encoded_image_checks.h"
#include "image/regular_file.h"
#include "scene/glb_layout.h"
#include "scene/gltf_index_ranges.h"
#include "scene/gltf_json_checks.h"
#include "scene/gltf_unknown_members.h"
#include "scene/parse_gltf_json.h"

namespace vkdr {
namespace {

std::string lowercaseExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

// tinygltf ends most messages with a newline, and quotes a data URI whole (megabytes,
// perhaps); one-line messages with the URI's start read better.
std::string trimmed(std::string text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
        text.pop_back();
    }
    constexpr size_t kShownCharacters = 48;
    for (size_t start = text.find("data:"); start != std::string::npos; start = text.find("data:", start + 1)) {
        size_t end = text.find_first_of(" '\"\n", start);
        if (end == std::string::npos) end = text.size();
        if (end - start > kShownCharacters + 16) {
            text.replace(start + kShownCharacters, end - start - kShownCharacters,
                         "... (" + std::to_string(end - start) + " characters)");
        }
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

// tinygltf asks for an external file as the base directory we give it joined with the
// decoded URI, then as "./" joined with it (the working directory). The callbacks give
// back only what SceneFiles allows, relative to the scene's directory.
struct FileAccessState {
    const SceneFiles& files;
    std::string prefix;  // the base directory as tinygltf joins it: ending in '/'
    std::vector<SourceFile>& read;  // the files read
};

// The decoded URI in a path tinygltf asks for; nullopt for its working-directory guess.
std::optional<std::string> requestedPath(const std::string& path, const FileAccessState& state) {
    if (path.rfind(state.prefix, 0) != 0) return std::nullopt;
    return path.substr(state.prefix.size());
}

bool fileExists(const std::string& path, void* user) {
    const auto& state = *static_cast<const FileAccessState*>(user);
    std::optional<std::string> requested = requestedPath(path, state);
    return requested && state.files.resolvePath(*requested).problem.empty();
}

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* user) {
    auto& state = *static_cast<FileAccessState*>(user);
    std::optional<std::string> requested = requestedPath(path, state);
    ResolvedFile resolved = requested ? state.files.resolvePath(*requested) : ResolvedFile{{}, "is not read"};
    if (!resolved.problem.empty()) {
        *error = "'" + requested.value_or(path) + "' " + resolved.problem;
        return false;
    }
    try {
        std::string bytes = readRegularFile(resolved.file);
        out->assign(bytes.begin(), bytes.end());
        state.read.push_back({resolved.file, contentDigest(bytes)});
        return true;
    } catch (const Error& e) {
        *error = e.what();
        return false;
    }
}

bool writeWholeFile(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
    *error = "the scene loader writes no files";
    return false;
}

// tinygltf reads a data URI of these media types, in base64, and takes any other for a
// file's name ("File not found").
constexpr std::array kReadDataUriPrefixes = {
    "data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,", "data:image/png;base64,",
    "data:image/jpeg;base64,", "data:image/bmp;base64,", "data:image/gif;base64,", "data:text/plain;base64,"};

void requireReadableDataUri(const std::string& uri, const std::string& field, const GltfDiagnostics& diagnostics) {
    for (std::string_view prefix : kReadDataUriPrefixes) {
        if (uri.rfind(prefix, 0) == 0) return;
    }
    if (uri.find(',') == std::string::npos) {
        diagnostics.fail(field, "a data URI holds its data after a ',', and this one has none");
    }
    const std::string header = uri.substr(0, std::min<size_t>(uri.find(','), 60));
    diagnostics.fail(field, "a data URI is read in base64, with the media type application/octet-stream or "
                            "application/gltf-buffer for a buffer, image/png, image/jpeg or image/bmp for an image; "
                            "this one starts '" + header + "'");
}

// Every external buffer and image is checked before tinygltf reads any, so that a
// refusal names the field, and tinygltf's own messages (which give a file's size) are
// only ever about files the scene may read.
void requireReadableUris(const nlohmann::json& document, const SceneFiles& files,
                         const GltfDiagnostics& diagnostics) {
    for (const char* array : {"buffers", "images"}) {
        if (!document.contains(array) || !document[array].is_array()) continue;
        for (size_t i = 0; i < document[array].size(); ++i) {
            const nlohmann::json& entry = document[array][i];
            if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
            std::string uri = entry["uri"].get<std::string>();
            if (isDataUri(uri)) {
                requireReadableDataUri(uri, indexed(array, i) + ".uri", diagnostics);
                continue;
            }
            ResolvedFile resolved = files.resolveUri(uri);
            if (!resolved.problem.empty()) diagnostics.fail(indexed(array, i) + ".uri", resolved.problem);
        }
    }
}

// In a GLB only buffers[0] stands for the BIN chunk by leaving out its uri; tinygltf
// would give any buffer without one the chunk's bytes. A .gltf has no chunk.
void requireBufferUris(const nlohmann::json& document, bool binary, const GltfDiagnostics& diagnostics) {
    if (!document.contains("buffers") || !document["buffers"].is_array()) return;
    for (size_t i = binary ? 1 : 0; i < document["buffers"].size(); ++i) {
        const nlohmann::json& buffer = document["buffers"][i];
        if (buffer.is_object() && !buffer.contains("uri")) {
            diagnostics.fail(indexed("buffers", i) + ".uri",
                             binary ? "missing: only buffers[0] may leave out its uri, to stand for the GLB's BIN "
                                      "chunk"
                                    : "missing: a buffer of a .gltf file needs one (only a .glb's first buffer may "
                                      "leave it out)");
        }
    }
}

// The JSON of a GLB file, after warning about the chunks tinygltf skips.
std::string_view glbJson(std::string_view bytes, GltfDiagnostics& diagnostics) {
    GlbLayout layout = glbLayout(bytes);
    if (!layout.problem.empty()) diagnostics.fail("", "cannot parse glTF: " + layout.problem);
    for (const std::string& ignored : layout.ignored) diagnostics.warn("", ignored);
    return layout.json;
}

}  // namespace

tinygltf::Model readGltfModel(const std::filesystem::path& file, const SceneFileAccess& access,
                              GltfDiagnostics& diagnostics, std::vector<SourceFile>& sources) {
    std::string extension = lowercaseExtension(file);
    if (extension != ".gltf" && extension != ".glb") {
        diagnostics.fail("", "expected a .gltf or .glb file");
    }
    std::string reason = notRegularFileReason(file);
    if (!reason.empty()) diagnostics.fail("", reason);
    std::string bytes = readRegularFile(file);
    if (bytes.size() > UINT32_MAX) diagnostics.fail("", "larger than 4 GiB, the most a glTF file may be");
    std::error_code unresolvable;
    sources.push_back({std::filesystem::weakly_canonical(file, unresolvable), contentDigest(bytes)});

    bool binary = extension == ".glb";
    SceneFiles files(file, access);
    const nlohmann::json document =
        parseGltfJson(binary ? glbJson(bytes, diagnostics) : std::string_view(bytes), diagnostics);
    // A document that is not a JSON object is left to tinygltf, which says what is wrong with it.
    if (document.is_object()) {
        requireWellFormedJson(document, diagnostics);
        requireIndicesInRange(document, diagnostics);
        requireBufferUris(document, binary, diagnostics);
        requireReadableUris(document, files, diagnostics);
        warnOfUnknownMembers(document, diagnostics);
    }

    std::string baseDirectory = files.directory().string();
    FileAccessState state{files, baseDirectory.back() == '/' ? baseDirectory : baseDirectory + "/", sources};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({fileExists, expandFilePath, readWholeFile, writeWholeFile, &state});
    loader.SetImageLoader(loadBoundedImage, nullptr);
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    bool loaded = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, data, unsigned(bytes.size()),
                                                       baseDirectory)
                         : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(),
                                                      unsigned(bytes.size()), baseDirectory);
    if (!loaded) {
        diagnostics.fail("", "cannot parse glTF: " + trimmed(error.empty() ? warning : error));
    }
    if (!trimmed(warning).empty()) {
        diagnostics.warn("", trimmed(warning));
    }
    return model;
}

}  // namespace vkdr
