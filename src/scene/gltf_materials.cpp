#include "scene/gltf_materials.h"

#include <algorithm>
#include <set>

#include "scene/gltf_media.h"
#include "scene/gltf_textures.h"
#include "scene/gltf_values.h"
#include "scene/parameter_kinds.h"
#include "scene/unique_name.h"

namespace vkdr {
namespace {

// A material keeps its glTF name where it is the first to use it; the others (unnamed, or
// repeating an earlier name) get their index as text, followed by '_' as often as it takes
// to differ from every other material's name ("1" may be another material's own name).
std::vector<std::string> uniqueMaterialNames(const tinygltf::Model& model,
                                             GltfDiagnostics& diagnostics) {
    std::vector<std::string> names(model.materials.size());
    std::set<std::string> taken;
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const std::string& name = model.materials[i].name;
        if (!name.empty() && taken.insert(name).second) {
            names[i] = name;
        }
    }
    for (size_t i = 0; i < model.materials.size(); ++i) {
        if (!names[i].empty()) {
            continue;
        }
        std::string name = firstFreeName(std::to_string(i), [&](const std::string& n) { return taken.count(n) > 0; });
        taken.insert(name);
        const std::string& given = model.materials[i].name;
        if (!given.empty()) {
            diagnostics.warn(indexed("materials", i) + ".name",
                             "'" + given + "' is used by an earlier material; this one is named '" + name + "'");
        } else if (name != std::to_string(i)) {
            diagnostics.warn(indexed("materials", i),
                             "unnamed, and its index is another material's name; this one is named '" + name + "'");
        }
        names[i] = std::move(name);
    }
    return names;
}

void requireRange(const GltfDiagnostics& diagnostics, glm::vec3 rgb, float low, float high,
                  const std::string& field) {
    for (int c = 0; c < 3; ++c) {
        if (rgb[c] < low || rgb[c] > high) {
            diagnostics.fail(indexed(field, size_t(c)),
                             "must be in [" + formatNumber(low) + ", " + formatNumber(high) +
                                 "], got " + formatNumber(rgb[c]));
        }
    }
}

void warnAboutIgnoredProperties(const tinygltf::Material& material, size_t index,
                                GltfDiagnostics& diagnostics) {
    if (material.normalTexture.index >= 0 || material.occlusionTexture.index >= 0 ||
        material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0) {
        diagnostics.warn("", "normal, occlusion and metallic-roughness textures are ignored; "
                             "surfaces are Lambertian");
    }
    const std::string field = indexed("materials", index) + ".alphaMode";
    if (material.alphaMode != "OPAQUE" && material.alphaMode != "MASK" && material.alphaMode != "BLEND") {
        diagnostics.warn(field, "'" + material.alphaMode + "' is not one of glTF's alpha modes (OPAQUE, MASK, "
                                "BLEND); the surface is opaque");
    } else if (material.alphaMode != "OPAQUE") {
        diagnostics.warn(field, "alpha is ignored; the surface is opaque");
    }
}

// emissiveFactor x KHR_materials_emissive_strength, held to the range of
// lights/<material>/emission (at most kMaxRadiance); the factor is in [0, 1].
glm::vec3 emission(const tinygltf::Material& material, size_t index, const GltfDiagnostics& diagnostics) {
    std::string field = indexed("materials", index);
    glm::vec3 factor = rgbFromFactor(diagnostics, material.emissiveFactor, field + ".emissiveFactor");
    requireRange(diagnostics, factor, 0.0f, 1.0f, field + ".emissiveFactor");
    auto extension = material.extensions.find("KHR_materials_emissive_strength");
    if (extension == material.extensions.end()) {
        return factor;
    }
    std::string strengthField = field + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
    double strength = readNumber(diagnostics, extension->second,
                                 field + ".extensions.KHR_materials_emissive_strength", "emissiveStrength", 1.0);
    if (strength < 0.0) {
        diagnostics.fail(strengthField, "must be >= 0, got " + formatNumber(strength));
    }
    for (int c = 0; c < 3; ++c) {
        float radiance = factor[c] * float(strength);
        if (std::string problem = valueProblem(describe(ParameterKind::Emission), radiance); !problem.empty()) {
            diagnostics.fail(strengthField, "the emission, emissiveFactor[" + std::to_string(c) +
                                                "] x emissiveStrength, " + problem);
        }
    }
    return factor * float(strength);
}

}  // namespace

void readMaterials(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene) {
    SrgbTextureCache textures(model, diagnostics, scene.textures);
    std::vector<std::string> names = uniqueMaterialNames(model, diagnostics);
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& source = model.materials[i];
        std::string field = indexed("materials", i);
        Material material;
        material.name = names[i];
        material.doubleSided = source.doubleSided;

        if (std::optional<Medium> medium = readMaterialMedium(source, i, material.name, diagnostics)) {
            if (hasEmissiveFactor(source) || source.emissiveTexture.index >= 0) {
                diagnostics.warn(field, "a medium boundary does not emit: its emissiveFactor and emissiveTexture "
                                        "are ignored (an emitting medium has an emission of its own)");
            }
            scene.media.push_back(std::move(*medium));
            material.interiorMedium = int32_t(scene.media.size() - 1);
            scene.materials.push_back(std::move(material));
            continue;  // a pass-through boundary has no colour and does not emit
        }

        warnAboutIgnoredProperties(source, i, diagnostics);
        std::string baseColorField = field + ".pbrMetallicRoughness.baseColorFactor";
        material.baseColor = rgbFromFactor(diagnostics, source.pbrMetallicRoughness.baseColorFactor,
                                           baseColorField);
        requireRange(diagnostics, material.baseColor, 0.0f, 1.0f, baseColorField);
        const auto baseColorMap = textures.textureFor(source.pbrMetallicRoughness.baseColorTexture,
                                                      field + ".pbrMetallicRoughness.baseColorTexture");
        material.baseColorTexture = baseColorMap.texture;
        material.baseColorMapping = baseColorMap.mapping;

        if (!source.emissiveFactor.empty()) {
            material.emission = emission(source, i, diagnostics);
        }
        // A factor times a strength of 0 still marks an emitter, as a fitted scene whose
        // emission reached 0 is written, so that its parameter stays.
        material.emitter = material.isEmissive() || hasEmissiveFactor(source);
        const auto emissionMap = textures.textureFor(source.emissiveTexture, field + ".emissiveTexture");
        material.emissionTexture = emissionMap.texture;
        material.emissionMapping = emissionMap.mapping;
        scene.materials.push_back(std::move(material));
    }
}

bool hasEmissiveFactor(const tinygltf::Material& material) {
    return std::any_of(material.emissiveFactor.begin(), material.emissiveFactor.end(),
                       [](double factor) { return factor > 0.0; });
}

}  // namespace vkdr
