#include "scene/gltf_media.h"

#include <cmath>
#include <limits>
#include <span>

#include "scene/gltf_values.h"
#include "scene/parameter_kinds.h"
#include "scene/scene_medium_emission.h"

namespace vkdr {
namespace {

const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions,
                                     const std::string& name) {
    auto found = extensions.find(name);
    return found == extensions.end() ? nullptr : &found->second;
}

// The loader accepts what --set accepts: each value within its parameter kind's range.
void requireInRange(const GltfDiagnostics& diagnostics, ParameterKind kind, std::span<const float> values,
                    const std::string& field) {
    for (float value : values) {
        if (std::string problem = valueProblem(describe(kind), value); !problem.empty()) {
            diagnostics.fail(field, problem);
        }
    }
}

Medium readParticipatingMedia(const tinygltf::Value& extension, const std::string& field,
                              std::string name, const GltfDiagnostics& diagnostics) {
    if (!extension.IsObject()) {
        diagnostics.fail(field, "expected an object");
    }
    Medium medium;
    medium.name = std::move(name);
    medium.sigma_a = readRgbOrScalar(diagnostics, extension, field, "sigma_a", glm::vec3(0.0f));
    medium.sigma_s = readRgbOrScalar(diagnostics, extension, field, "sigma_s", glm::vec3(0.0f));
    medium.g = float(readNumber(diagnostics, extension, field, "g", 0.0));
    // An emission grid's strengths are emitted white unless the emission says otherwise.
    const glm::vec3 defaultEmission(extension.Has("emissionGrid") ? 1.0f : 0.0f);
    medium.emission = readRgbOrScalar(diagnostics, extension, field, "emission", defaultEmission);
    requireInRange(diagnostics, ParameterKind::SigmaA, {&medium.sigma_a.x, 3}, field + ".sigma_a");
    requireInRange(diagnostics, ParameterKind::SigmaS, {&medium.sigma_s.x, 3}, field + ".sigma_s");
    requireInRange(diagnostics, ParameterKind::G, {&medium.g, 1}, field + ".g");
    requireInRange(diagnostics, ParameterKind::MediumEmission, {&medium.emission.x, 3}, field + ".emission");
    return medium;
}

// KHR_materials_volume describes absorption only: light that travels attenuationDistance
// keeps the fraction attenuationColor, so sigma_a = -ln(attenuationColor) / distance.
Medium readVolumeAttenuation(const tinygltf::Value& volume, const std::string& field,
                             std::string name, const GltfDiagnostics& diagnostics) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    double distance = kInfinity;
    if (volume.Has("attenuationDistance")) {
        distance = readNumber(diagnostics, volume, field, "attenuationDistance", kInfinity);
        if (distance <= 0.0) {
            diagnostics.fail(field + ".attenuationDistance",
                             "must be > 0, got " + formatNumber(distance));
        }
    }
    glm::vec3 color = readRgbOrScalar(diagnostics, volume, field, "attenuationColor", glm::vec3(1.0f));
    Medium medium;
    medium.name = std::move(name);
    for (int c = 0; c < 3; ++c) {
        std::string colorField = indexed(field + ".attenuationColor", size_t(c));
        if (color[c] == 0.0f) {
            diagnostics.fail(colorField, "0 means infinite absorption; use a small positive value");
        }
        if (color[c] < 0.0f || color[c] > 1.0f) {
            diagnostics.fail(colorField, "must be in (0, 1], got " + formatNumber(color[c]));
        }
        medium.sigma_a[c] = std::isinf(distance) ? 0.0f : float(-std::log(double(color[c])) / distance);
        if (std::string problem = valueProblem(describe(ParameterKind::SigmaA), medium.sigma_a[c]);
            !problem.empty()) {
            diagnostics.fail(field + ".attenuationDistance",
                             "too small for attenuationColor " + formatNumber(color[c]) +
                                 ": sigma_a = -ln(attenuationColor) / attenuationDistance " + problem);
        }
    }
    return medium;
}

}  // namespace

std::optional<Medium> readMaterialMedium(const tinygltf::Material& material,
                                         size_t materialIndex, const std::string& mediumName,
                                         GltfDiagnostics& diagnostics) {
    std::string extensionsField = indexed("materials", materialIndex) + ".extensions";
    const tinygltf::Value* participatingMedia = findExtension(material.extensions, kMediumExtension);
    const tinygltf::Value* transmission =
        findExtension(material.extensions, "KHR_materials_transmission");
    std::string transmissionField = extensionsField + ".KHR_materials_transmission";

    double transmissionFactor = 0.0;
    if (transmission) {
        transmissionFactor =
            readNumber(diagnostics, *transmission, transmissionField, "transmissionFactor", 0.0);
        if (transmission->Has("transmissionTexture")) {
            diagnostics.warn(transmissionField + ".transmissionTexture", "ignored");
        }
    }
    if (transmissionFactor > 0.0) {
        const tinygltf::Value* iorExtension = findExtension(material.extensions, "KHR_materials_ior");
        std::string iorField = extensionsField + ".KHR_materials_ior";
        double ior = iorExtension ? readNumber(diagnostics, *iorExtension, iorField, "ior", 1.5) : 1.5;
        if (ior != 1.0) {
            diagnostics.fail(iorField + ".ior",
                             "refraction is not supported: a transmissive material must have "
                             "ior 1 (a pass-through medium boundary), got " + formatNumber(ior) +
                                 (iorExtension ? "" : " (the default when absent)"));
        }
        if (transmissionFactor != 1.0) {
            diagnostics.fail(transmissionField + ".transmissionFactor",
                             "partial transmission is not supported: must be 0 or 1, got " +
                                 formatNumber(transmissionFactor));
        }
    }

    if (participatingMedia) {
        return readParticipatingMedia(*participatingMedia, extensionsField + "." + kMediumExtension,
                                      mediumName, diagnostics);
    }
    if (transmissionFactor != 1.0) {
        // glTF's volume lies behind a transmissive surface only: without one it is not seen.
        if (findExtension(material.extensions, "KHR_materials_volume")) {
            diagnostics.warn(extensionsField + ".KHR_materials_volume",
                             "ignored: without KHR_materials_transmission (transmissionFactor 1) the surface is "
                             "opaque and no medium lies inside it");
        }
        return std::nullopt;
    }
    if (const tinygltf::Value* volume = findExtension(material.extensions, "KHR_materials_volume")) {
        return readVolumeAttenuation(*volume, extensionsField + ".KHR_materials_volume",
                                     mediumName, diagnostics);
    }
    diagnostics.warn(transmissionField, "transmission 1 and ior 1 without KHR_materials_volume: "
                                        "treated as the boundary of a non-absorbing medium");
    Medium clear;
    clear.name = mediumName;
    return clear;
}

std::optional<Medium> readSceneMedium(const tinygltf::Model& model, GltfDiagnostics& diagnostics) {
    const tinygltf::Value* extension = findExtension(model.extensions, kMediumExtension);
    if (!extension) {
        return std::nullopt;
    }
    std::string field = std::string("extensions.") + kMediumExtension;
    std::string name = extension->IsObject()
                           ? readString(diagnostics, *extension, field, "name", "scene")
                           : "scene";
    if (name.empty()) {
        diagnostics.fail(field + ".name", "must not be empty");
    }
    return readParticipatingMedia(*extension, field, name, diagnostics);
}

void requireAttenuatedSceneEmission(const Scene& scene, GltfDiagnostics& diagnostics) {
    if (std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(scene)) {
        diagnostics.fail(indexed(std::string("extensions.") + kMediumExtension + ".emission", size_t(unbounded->channel)),
                         unbounded->problem);
    }
}

glm::vec3 readBackground(const tinygltf::Model& model, GltfDiagnostics& diagnostics) {
    const tinygltf::Value* extension = findExtension(model.extensions, kBackgroundExtension);
    if (!extension) {
        return glm::vec3(0.0f);
    }
    std::string field = std::string("extensions.") + kBackgroundExtension;
    if (!extension->IsObject()) {
        diagnostics.fail(field, "expected an object");
    }
    glm::vec3 radiance = readRgbOrScalar(diagnostics, *extension, field, "radiance", glm::vec3(0.0f));
    // A radiance, held to the range of an emitter's.
    requireInRange(diagnostics, ParameterKind::Emission, {&radiance.x, 3}, field + ".radiance");
    return radiance;
}

}  // namespace vkdr
