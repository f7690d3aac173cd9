#include "scene/write_scene.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "image/atomic_write.h"
#include "image/image.h"
#include "image/output_paths.h"
#include "image/regular_file.h"
#include "scene/glb_layout.h"
#include "scene/gltf_diagnostics.h"
#include "scene/parse_gltf_json.h"
#include "scene/scene_file_access.h"
#include "scene/scene_medium_emission.h"
#include "volume/write_density_grid.h"

namespace vkdr {
namespace {

using nlohmann::json;

constexpr const char* kMediumExtension = "VKDR_participating_media";
constexpr const char* kVolumeExtension = "KHR_materials_volume";
constexpr const char* kStrengthExtension = "KHR_materials_emissive_strength";

// The glTF JSON, and for a .glb the binary chunk that its first buffer refers to.
struct GltfSource {
    json document;
    std::optional<std::string> binaryChunk;
};

[[noreturn]] void failReading(const std::filesystem::path& file, const std::string& reason) {
    throw Error(file.string() + ": " + reason);
}

// The JSON read by the loader's own rules (scene/parse_gltf_json.h): the file is the one
// the scene was loaded from, but a file that is not among the scene's sources (its path
// changed since) is read here for the first time.
json parseDocument(const std::filesystem::path& file, std::string_view text) {
    json document = parseGltfJson(text, GltfDiagnostics(file.string()));
    if (!document.is_object()) failReading(file, "its JSON is not an object");
    return document;
}

GltfSource parseGlb(const std::filesystem::path& file, const std::string& bytes) {
    GlbLayout layout = glbLayout(bytes);
    if (!layout.problem.empty()) failReading(file, layout.problem);
    GltfSource source{parseDocument(file, layout.json), std::nullopt};
    if (layout.binary) source.binaryChunk = std::string(*layout.binary);
    return source;
}

GltfSource readGltfSource(const std::filesystem::path& file, const std::vector<SourceFile>& sources) {
    std::string bytes = readRegularFile(file);
    requireUnchangedSource(sources, file, bytes);
    if (file.extension() == ".glb" || file.extension() == ".GLB") {
        return parseGlb(file, bytes);
    }
    return {parseDocument(file, bytes), std::nullopt};
}

// The shortest decimal that reads back as `value`, so 0.05f is written as 0.05 and
// the loader gets exactly the float it was given.
double exactJsonNumber(float value) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text) - 1, value);
    *end = '\0';
    return std::strtod(text, nullptr);
}

json rgbJson(glm::vec3 rgb) {
    return json::array({exactJsonNumber(rgb.r), exactJsonNumber(rgb.g), exactJsonNumber(rgb.b)});
}

float largestChannel(glm::vec3 rgb) { return std::max({rgb.r, rgb.g, rgb.b}); }

void declareExtensionUsed(json& document, const std::string& name) {
    json& used = document["extensionsUsed"];
    if (!used.is_array()) used = json::array();
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

void writeParticipatingMedia(json& extension, const Medium& medium) {
    extension["sigma_a"] = rgbJson(medium.sigma_a);
    extension["sigma_s"] = rgbJson(medium.sigma_s);
    extension["g"] = exactJsonNumber(medium.g);
    // With an emission grid, an emission left out would read back as white.
    if (medium.isEmissive() || medium.hasEmissionGrid() || extension.contains("emission")) {
        extension["emission"] = rgbJson(medium.emission);
    }
}

// sigma_a = -ln(attenuationColor) / attenuationDistance. The distance over which the
// densest channel keeps 1/e keeps every colour well inside (0, 1], so the float colour
// the loader reads gives sigma_a back to float precision (or close, for channels far
// thinner than the densest).
void writeVolumeAttenuation(json& volume, glm::vec3 sigma_a) {
    // A thicknessFactor of 0, glTF's default, makes the material thin-walled for other
    // tools, which then apply no attenuation; vkdiffrender follows the mesh's own
    // thickness and reads the attenuation whatever it says.
    const auto thickness = volume.find("thicknessFactor");
    if (thickness == volume.end() || !thickness->is_number() || !(thickness->get<double>() > 0.0)) {
        volume["thicknessFactor"] = 1.0;
    }
    float densest = largestChannel(sigma_a);
    if (densest == 0.0f) {
        volume.erase("attenuationDistance");  // absent = infinite: no absorption
        volume["attenuationColor"] = json::array({1.0, 1.0, 1.0});
        return;
    }
    double distance = 1.0 / double(densest);
    json color = json::array();
    for (int c = 0; c < 3; ++c) {
        color.push_back(std::exp(-double(sigma_a[c]) * distance));
    }
    volume["attenuationColor"] = color;
    volume["attenuationDistance"] = distance;
}

void writeEnclosedMedium(json& document, json& material, const Medium& medium) {
    json& extensions = material["extensions"];
    bool hasOwnSpelling = extensions.contains(kMediumExtension);
    bool absorbsOnly = medium.sigma_s == glm::vec3(0.0f) && medium.g == 0.0f && !medium.isEmissive();
    // KHR_materials_volume describes absorption only; our spelling, which wins when a
    // material has both, carries the scattering and the emission.
    if (hasOwnSpelling || !absorbsOnly) {
        writeParticipatingMedia(extensions[kMediumExtension], medium);
        declareExtensionUsed(document, kMediumExtension);
    }
    // Kept consistent for other glTF tools, which read only the Khronos spelling.
    if (!hasOwnSpelling || extensions.contains(kVolumeExtension)) {
        writeVolumeAttenuation(extensions[kVolumeExtension], medium.sigma_a);
        declareExtensionUsed(document, kVolumeExtension);
    }
}

void writeBaseColor(json& material, glm::vec3 baseColor) {
    json& pbr = material["pbrMetallicRoughness"];
    const json* old = pbr.contains("baseColorFactor") ? &pbr["baseColorFactor"] : nullptr;
    double alpha = old && old->is_array() && old->size() == 4 ? (*old)[3].get<double>() : 1.0;
    json factor = rgbJson(baseColor);
    factor.push_back(alpha);
    pbr["baseColorFactor"] = factor;
}

// glTF caps emissiveFactor at 1; the strength extension carries the rest. An emitter
// whose emission is 0 is written as a factor of 1 times a strength of 0, which the
// loader still reads as an emitter, so a fitted scene keeps its emission parameter.
void writeEmission(json& document, json& material, const Material& source) {
    const glm::vec3 emission = source.emission;
    if (!source.emitter && emission == glm::vec3(0.0f) && !material.contains("emissiveFactor")) {
        return;
    }
    if (source.emitter && emission == glm::vec3(0.0f)) {
        material["emissiveFactor"] = rgbJson(glm::vec3(1.0f));
        material["extensions"][kStrengthExtension]["emissiveStrength"] = 0;
        declareExtensionUsed(document, kStrengthExtension);
        return;
    }
    float strength = std::max(1.0f, largestChannel(emission));
    material["emissiveFactor"] = rgbJson(emission / strength);
    if (strength > 1.0f) {
        material["extensions"][kStrengthExtension]["emissiveStrength"] = exactJsonNumber(strength);
        declareExtensionUsed(document, kStrengthExtension);
    } else if (material.contains("extensions")) {
        material["extensions"].erase(kStrengthExtension);
        if (material["extensions"].empty()) material.erase("extensions");
    }
}

void writeSurface(json& document, json& material, const Material& source) {
    writeBaseColor(material, source.baseColor);
    writeEmission(document, material, source);
}

// The loader gives primitives without a material glTF's default material, named
// "default", after the file's own. If the fit changed it, it becomes a real material.
void writeDefaultMaterial(json& document, const Material& fallback) {
    if (fallback.baseColor == glm::vec3(1.0f) && fallback.emission == glm::vec3(0.0f)) {
        return;
    }
    json material = {{"name", fallback.name}};
    writeSurface(document, material, fallback);
    json& materials = document["materials"];
    materials.push_back(material);
    size_t index = materials.size() - 1;
    for (json& mesh : document["meshes"]) {
        for (json& primitive : mesh["primitives"]) {
            if (!primitive.contains("material")) primitive["material"] = index;
        }
    }
}

void writeMaterials(json& document, const Scene& scene, const std::filesystem::path& original) {
    size_t fileMaterials = document.contains("materials") ? document["materials"].size() : 0;
    if (scene.materials.size() < fileMaterials || scene.materials.size() > fileMaterials + 1) {
        failReading(original, "has " + std::to_string(fileMaterials) + " materials; the scene to write back has " +
                                  std::to_string(scene.materials.size()) + " (was it loaded from this file?)");
    }
    for (size_t i = 0; i < fileMaterials; ++i) {
        json& material = document["materials"][i];
        const Material& source = scene.materials[i];
        if (source.isMediumBoundary()) {
            writeEnclosedMedium(document, material, scene.media[size_t(source.interiorMedium)]);
        } else {
            writeSurface(document, material, source);
        }
    }
    if (scene.materials.size() > fileMaterials) {
        writeDefaultMaterial(document, scene.materials.back());
    }
}

void writeSceneMedium(json& document, const Scene& scene) {
    if (scene.sceneMedium == kNoMedium) {
        return;
    }
    writeParticipatingMedia(document["extensions"][kMediumExtension], scene.media[size_t(scene.sceneMedium)]);
}

// A light's colour stays in [0, 1] as glTF asks: the brightest channel becomes the
// intensity (the old colour is kept for a light whose intensity is 0).
void writePunctualLights(json& document, const Scene& scene, const std::filesystem::path& original) {
    if (scene.punctualLights.empty()) {
        return;
    }
    json& lights = document["extensions"]["KHR_lights_punctual"]["lights"];
    if (!lights.is_array() || lights.size() != scene.punctualLights.size()) {
        failReading(original, "its KHR_lights_punctual lights differ from the scene's to write back (was it loaded "
                              "from this file?)");
    }
    for (size_t i = 0; i < lights.size(); ++i) {
        const glm::vec3 intensity = scene.punctualLights[i].intensity;
        const float brightest = largestChannel(intensity);
        lights[i]["intensity"] = exactJsonNumber(brightest);
        if (brightest > 0.0f) {
            lights[i]["color"] = rgbJson(intensity / brightest);
        }
    }
}

// A file the written scene consists of may not be one the scene was loaded from (the
// original, a buffer, an image, a grid): that file would change under the scene that
// reads it.
void requireNotASource(const std::vector<SourceFile>& sources, const std::filesystem::path& file) {
    for (const SourceFile& source : sources) {
        if (sameFile(file, source.file)) {
            throw Error(file.string() + ": the written scene would replace this file, which the scene reads; write "
                        "the scene under another name or in another directory");
        }
    }
}

// The files beside the .gltf that the written scene consists of, each with what writes
// it. They are written only once every one has been checked: a refusal leaves a scene
// written before under the same name whole, not half replaced.
class FilesBeside {
public:
    void add(std::filesystem::path file, std::function<void()> write) {
        files_.push_back({std::move(file), std::move(write)});
    }
    void requireNoneIsASource(const std::vector<SourceFile>& sources) const {
        for (const File& file : files_) requireNotASource(sources, file.path);
    }
    void write() const {
        for (const File& file : files_) file.write();
    }

private:
    struct File {
        std::filesystem::path path;
        std::function<void()> write;
    };
    std::vector<File> files_;
};

// The written scene must load by the same rule as any other (scene_file_access.h): files
// the original refers to stay where they are when they lie in the output's directory
// tree, and are copied beside the output, as <stem>.<array><i><extension>, when not.
// Entries of `array` marked in `rewritten` are written anew by others and left alone.
void referToExternalFiles(json& document, const char* array, const std::filesystem::path& original,
                          const std::vector<SourceFile>& sources, const std::filesystem::path& out,
                          FilesBeside& beside, const std::vector<bool>& rewritten = {}) {
    if (!document.contains(array) || !document[array].is_array()) {
        return;
    }
    // The original has been loaded by its own rule already; here its files only need finding.
    SceneFiles from(original, SceneFileAccess{true});
    std::error_code ec;
    std::filesystem::path toDirectory =
        std::filesystem::weakly_canonical(std::filesystem::absolute(out).parent_path(), ec);
    for (size_t i = 0; i < document[array].size(); ++i) {
        json& entry = document[array][i];
        if ((i < rewritten.size() && rewritten[i]) || !entry.contains("uri") || !entry["uri"].is_string() ||
            isDataUri(entry["uri"].get<std::string>())) {
            continue;
        }
        ResolvedFile resolved = from.resolveUri(entry["uri"].get<std::string>());
        if (!resolved.problem.empty()) {
            failReading(original, std::string(array) + "[" + std::to_string(i) + "].uri: " + resolved.problem);
        }
        std::string bytes = readRegularFile(resolved.file);
        requireUnchangedSource(sources, resolved.file, bytes);
        std::filesystem::path relative = resolved.file.lexically_relative(toDirectory);
        if (relative.empty() || *relative.begin() == "..") {
            relative = out.stem().string() + "." + array + std::to_string(i) + resolved.file.extension().string();
            const std::filesystem::path copy = toDirectory / relative;
            beside.add(copy, [copy, bytes = std::move(bytes)] {
                writeAtomically(copy, [&](std::ofstream& stream) {
                    stream.write(bytes.data(), std::streamsize(bytes.size()));
                });
            });
        }
        entry["uri"] = encodeUriPath(relative.generic_string());
    }
}

// Grids are parameters too: each medium's density, emission and albedo grid, with its
// current voxels, is written beside `out` as <stem>.materials<i>.density.vdb (a
// material's medium) or <stem>.density.vdb (the scene medium), .emission_grid.vdb and
// .albedo_grid.vdb, and the medium's "density", "emissionGrid" and "albedoGrid" refer to
// those files.
void writeDensityGrids(json& document, const Scene& scene, const std::filesystem::path& out, FilesBeside& beside) {
    auto writeGrid = [&](json& owner, int32_t grid, const char* key, const char* defaultName,
                         const std::string& stem) {
        if (grid < 0 || !owner.contains("extensions") || !owner["extensions"].contains(kMediumExtension) ||
            !owner["extensions"][kMediumExtension].contains(key)) {
            return;
        }
        const DensityGrid& values = scene.densityGrids[size_t(grid)].grid;
        const std::string file = stem + ".vdb";
        const std::filesystem::path path = out.parent_path() / file;
        beside.add(path, [path, &values] { writeDensityGridVdb(path, values); });
        json& reference = owner["extensions"][kMediumExtension][key];
        reference["uri"] = encodeUriPath(file);
        reference["grid"] = values.name.empty() ? defaultName : values.name;
    };
    auto writeGrids = [&](json& owner, int32_t medium, const std::string& suffix) {
        if (medium < 0) {
            return;
        }
        const std::string stem = out.stem().string() + suffix;
        writeGrid(owner, scene.media[size_t(medium)].densityGrid, "density", "density", stem + ".density");
        writeGrid(owner, scene.media[size_t(medium)].emissionGrid, "emissionGrid", "flame", stem + ".emission_grid");
        writeGrid(owner, scene.media[size_t(medium)].albedoGrid, "albedoGrid", "color", stem + ".albedo_grid");
    };
    if (document.contains("materials") && document["materials"].is_array()) {
        for (size_t i = 0; i < document["materials"].size() && i < scene.materials.size(); ++i) {
            writeGrids(document["materials"][i], scene.materials[i].interiorMedium, ".materials" + std::to_string(i));
        }
    }
    writeGrids(document, scene.sceneMedium, "");
}

void writeBinaryChunkBeside(json& document, const GltfSource& source, const std::filesystem::path& original,
                            const std::filesystem::path& out, FilesBeside& beside) {
    if (!document.contains("buffers") || document["buffers"].empty() || document["buffers"][0].contains("uri")) {
        return;
    }
    json& buffer = document["buffers"][0];
    size_t byteLength = buffer.value("byteLength", size_t(0));
    if (!source.binaryChunk || source.binaryChunk->size() < byteLength) {
        failReading(original, "buffers[0] needs a binary chunk of " + std::to_string(byteLength) + " bytes");
    }
    std::filesystem::path binary = std::filesystem::path(out).replace_extension(".bin");
    // tinygltf requires an external buffer's file to be exactly byteLength long.
    beside.add(binary, [binary, &source, byteLength] {
        writeAtomically(binary, [&](std::ofstream& stream) {
            stream.write(source.binaryChunk->data(), std::streamsize(byteLength));
        });
    });
    buffer["uri"] = encodeUriPath(binary.filename().string());
}

Image textureImage(const Texture& texture) {
    Image image{texture.width, texture.height, {}};
    image.rgb.reserve(texture.texels.size() * 3);
    for (const glm::vec4& texel : texture.texels) {
        image.rgb.insert(image.rgb.end(), {texel.r, texel.g, texel.b});
    }
    return image;
}

// The glTF image of each material's base colour texture (-1 where it has none): the
// images whose texels are parameters.
std::vector<int64_t> baseColorImageOfMaterials(const json& document, const Scene& scene) {
    const size_t fileMaterials = document.contains("materials") ? document["materials"].size() : 0;
    std::vector<int64_t> images(std::min(fileMaterials, scene.materials.size()), -1);
    for (size_t i = 0; i < images.size(); ++i) {
        const Material& material = scene.materials[i];
        if (material.isMediumBoundary() || material.baseColorTexture < 0) {
            continue;
        }
        size_t texture = document["materials"][i]["pbrMetallicRoughness"]["baseColorTexture"]["index"].get<size_t>();
        images[i] = document["textures"][texture]["source"].get<int64_t>();
    }
    return images;
}

// Which of the document's images writeBaseColorTextures writes anew, from
// baseColorImageOfMaterials.
std::vector<bool> imagesWrittenAnew(const json& document, const std::vector<int64_t>& imageOfMaterials) {
    std::vector<bool> images(document.contains("images") ? document["images"].size() : 0, false);
    for (int64_t image : imageOfMaterials) {
        if (image >= 0) images[size_t(image)] = true;
    }
    return images;
}

// The texels of base colour textures are parameters too. Each such image is written
// beside `out` as <stem>.image<i>.png (8-bit sRGB, as glTF base colour textures are;
// alpha is not kept) and the glTF image refers to it instead of its old source.
// `images`: baseColorImageOfMaterials.
void writeBaseColorTextures(json& document, const Scene& scene, const std::vector<int64_t>& images,
                            const std::filesystem::path& out, FilesBeside& beside) {
    std::vector<bool> written(document.contains("images") ? document["images"].size() : 0, false);
    for (size_t i = 0; i < images.size(); ++i) {
        if (images[i] < 0 || written[size_t(images[i])]) {
            continue;
        }
        const size_t image = size_t(images[i]);
        std::string file = out.stem().string() + ".image" + std::to_string(image) + ".png";
        const std::filesystem::path path = out.parent_path() / file;
        const Texture& texture = scene.textures[size_t(scene.materials[i].baseColorTexture)];
        beside.add(path, [path, &texture] { writePng(path, textureImage(texture)); });
        json& entry = document["images"][image];
        entry.erase("bufferView");
        entry.erase("mimeType");
        entry["uri"] = encodeUriPath(file);
        written[image] = true;
    }
}

}  // namespace

void requireWritableDensityGrids(const Scene& scene) {
    for (const SceneDensityGrid& grid : scene.densityGrids) {
        const std::string problem = gridTransformWriteProblem(grid.grid.indexToLocal);
        if (!problem.empty()) {
            throw Error(grid.file.string() + ": grid '" + grid.grid.name + "': " + problem +
                        ", so the grid cannot be written beside a fitted scene.gltf; scale the grid's voxels up in "
                        "its file and down with the grid reference's \"node\"");
        }
    }
}

void writeSceneWithParameters(const std::filesystem::path& original, const Scene& scene,
                              const std::filesystem::path& out) {
    requireWritableDensityGrids(scene);
    // Parameters set one at a time can make a scene the loader refuses as a whole.
    if (std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(scene)) {
        throw Error(out.string() + ": the scene would not load again: " + unbounded->problem);
    }
    GltfSource source = readGltfSource(original, scene.sourceFiles);
    json& document = source.document;
    writeMaterials(document, scene, original);
    writeSceneMedium(document, scene);
    writePunctualLights(document, scene, original);

    FilesBeside beside;
    const std::vector<int64_t> baseColorImages = baseColorImageOfMaterials(document, scene);
    referToExternalFiles(document, "buffers", original, scene.sourceFiles, out, beside);
    referToExternalFiles(document, "images", original, scene.sourceFiles, out, beside,
                         imagesWrittenAnew(document, baseColorImages));
    writeDensityGrids(document, scene, out, beside);
    writeBinaryChunkBeside(document, source, original, out, beside);
    writeBaseColorTextures(document, scene, baseColorImages, out, beside);

    std::vector<SourceFile> reads = scene.sourceFiles;
    for (const SceneDensityGrid& grid : scene.densityGrids) reads.push_back({grid.file, 0});
    beside.requireNoneIsASource(reads);
    requireNotASource(reads, out);
    std::string text = document.dump(2);
    beside.write();
    writeAtomically(out, [&](std::ofstream& stream) { stream << text << '\n'; });
}

}  // namespace vkdr
