#include "scene/gltf_unknown_members.h"

#include <algorithm>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "scene/gltf_lights.h"

namespace vkdr {
namespace {

using json = nlohmann::json;
using Names = std::span<const std::string_view>;

// The glTF 2.0 schema's members of each object the loader reads ("extensions" and
// "extras" belong to every object).
constexpr std::string_view kDocument[] = {"asset",   "extensionsUsed", "extensionsRequired", "accessors", "animations",
                             "buffers", "bufferViews",    "cameras",            "images",    "materials",
                             "meshes",  "nodes",          "samplers",           "scene",     "scenes",
                             "skins",   "textures"};
constexpr std::string_view kAsset[] = {"copyright", "generator", "version", "minVersion"};
constexpr std::string_view kScene[] = {"nodes", "name"};
constexpr std::string_view kNode[] = {"camera", "children", "skin", "matrix", "mesh", "rotation", "scale", "translation",
                         "weights", "name"};
constexpr std::string_view kNodeLight[] = {"light"};
constexpr std::string_view kMesh[] = {"primitives", "weights", "name"};
constexpr std::string_view kPrimitive[] = {"attributes", "indices", "material", "mode", "targets"};
constexpr std::string_view kMaterial[] = {"name", "pbrMetallicRoughness", "normalTexture", "occlusionTexture", "emissiveTexture",
                             "emissiveFactor", "alphaMode", "alphaCutoff", "doubleSided"};
constexpr std::string_view kPbr[] = {"baseColorFactor", "baseColorTexture", "metallicFactor", "roughnessFactor",
                        "metallicRoughnessTexture"};
constexpr std::string_view kTextureInfo[] = {"index", "texCoord"};
constexpr std::string_view kNormalTextureInfo[] = {"index", "texCoord", "scale"};
constexpr std::string_view kOcclusionTextureInfo[] = {"index", "texCoord", "strength"};
constexpr std::string_view kCamera[] = {"orthographic", "perspective", "type", "name"};
constexpr std::string_view kOrthographic[] = {"xmag", "ymag", "zfar", "znear"};
constexpr std::string_view kPerspective[] = {"aspectRatio", "yfov", "zfar", "znear"};
constexpr std::string_view kAccessor[] = {"bufferView", "byteOffset", "componentType", "normalized", "count",
                             "type",       "max",        "min",           "sparse",     "name"};
constexpr std::string_view kSparse[] = {"count", "indices", "values"};
constexpr std::string_view kSparseIndices[] = {"bufferView", "byteOffset", "componentType"};
constexpr std::string_view kSparseValues[] = {"bufferView", "byteOffset"};
constexpr std::string_view kBufferView[] = {"buffer", "byteOffset", "byteLength", "byteStride", "target", "name"};
constexpr std::string_view kBuffer[] = {"uri", "byteLength", "name"};
constexpr std::string_view kImage[] = {"uri", "mimeType", "bufferView", "name"};
constexpr std::string_view kSampler[] = {"magFilter", "minFilter", "wrapS", "wrapT", "name"};
constexpr std::string_view kTexture[] = {"sampler", "source", "name"};
constexpr std::string_view kLightsExtension[] = {"lights"};
constexpr std::string_view kLight[] = {"name", "color", "intensity", "type", "range", "spot"};
constexpr std::string_view kSpot[] = {"innerConeAngle", "outerConeAngle"};

// `key` of `field`, or of the document where `field` is empty.
std::string memberOf(const std::string& field, std::string_view key) {
    return field.empty() ? std::string(key) : member(field, key);
}

// Warns of `object`'s members outside `known`; returns whether `object` is an object.
bool warnOfUnknown(const json& object, const std::string& field, Names known, GltfDiagnostics& diagnostics) {
    if (!object.is_object()) return false;
    for (const auto& [key, value] : object.items()) {
        if (key == "extensions" || key == "extras") continue;
        if (std::find(known.begin(), known.end(), key) != known.end()) continue;
        std::string names;
        for (std::string_view name : known) names += (names.empty() ? "" : ", ") + std::string(name);
        diagnostics.warn(memberOf(field, key), "unknown member, ignored (glTF's: " + names + ")");
    }
    return true;
}

// The member `key` of `object`, where there is one, checked against `known`.
void warnOfUnknownIn(const json& object, const std::string& field, std::string_view key, Names known,
                     GltfDiagnostics& diagnostics) {
    const std::string name(key);
    if (object.is_object() && object.contains(name)) {
        warnOfUnknown(object[name], memberOf(field, key), known, diagnostics);
    }
}

// Each entry of the array `key` of `object`, checked against `known`, and then passed to
// `inside` (with its field) where it is an object.
template <typename Inside>
void warnOfUnknownInEach(const json& object, const std::string& field, std::string_view key, Names known,
                         GltfDiagnostics& diagnostics, Inside inside) {
    const std::string name(key);
    if (!object.is_object() || !object.contains(name) || !object[name].is_array()) return;
    const std::string arrayField = memberOf(field, key);
    for (size_t i = 0; i < object[name].size(); ++i) {
        const std::string entryField = indexed(arrayField, i);
        if (warnOfUnknown(object[name][i], entryField, known, diagnostics)) inside(object[name][i], entryField);
    }
}

void warnOfUnknownInEach(const json& object, const std::string& field, std::string_view key, Names known,
                         GltfDiagnostics& diagnostics) {
    warnOfUnknownInEach(object, field, key, known, diagnostics, [](const json&, const std::string&) {});
}

const json* extension(const json& object, std::string_view name) {
    if (!object.contains("extensions") || !object["extensions"].is_object()) return nullptr;
    const auto found = object["extensions"].find(std::string(name));
    return found == object["extensions"].end() ? nullptr : &*found;
}

std::string extensionField(const std::string& field, std::string_view name) {
    return member(memberOf(field, "extensions"), name);
}

void warnOfUnknownInMaterial(const json& material, const std::string& field, GltfDiagnostics& diagnostics) {
    warnOfUnknownIn(material, field, "normalTexture", kNormalTextureInfo, diagnostics);
    warnOfUnknownIn(material, field, "occlusionTexture", kOcclusionTextureInfo, diagnostics);
    warnOfUnknownIn(material, field, "emissiveTexture", kTextureInfo, diagnostics);
    warnOfUnknownIn(material, field, "pbrMetallicRoughness", kPbr, diagnostics);
    if (material.contains("pbrMetallicRoughness")) {
        const json& pbr = material["pbrMetallicRoughness"];
        const std::string pbrField = member(field, "pbrMetallicRoughness");
        warnOfUnknownIn(pbr, pbrField, "baseColorTexture", kTextureInfo, diagnostics);
        warnOfUnknownIn(pbr, pbrField, "metallicRoughnessTexture", kTextureInfo, diagnostics);
    }
}

void warnOfUnknownInAccessor(const json& accessor, const std::string& field, GltfDiagnostics& diagnostics) {
    warnOfUnknownIn(accessor, field, "sparse", kSparse, diagnostics);
    if (accessor.contains("sparse") && accessor["sparse"].is_object()) {
        const std::string sparseField = member(field, "sparse");
        warnOfUnknownIn(accessor["sparse"], sparseField, "indices", kSparseIndices, diagnostics);
        warnOfUnknownIn(accessor["sparse"], sparseField, "values", kSparseValues, diagnostics);
    }
}

}  // namespace

void warnOfUnknownMembers(const json& document, GltfDiagnostics& diagnostics) {
    warnOfUnknown(document, "", kDocument, diagnostics);
    warnOfUnknownIn(document, "", "asset", kAsset, diagnostics);
    warnOfUnknownInEach(document, "", "scenes", kScene, diagnostics);
    warnOfUnknownInEach(document, "", "nodes", kNode, diagnostics, [&](const json& node, const std::string& field) {
        if (const json* light = extension(node, kPunctualLightsExtension)) {
            warnOfUnknown(*light, extensionField(field, kPunctualLightsExtension), kNodeLight, diagnostics);
        }
    });
    warnOfUnknownInEach(document, "", "meshes", kMesh, diagnostics, [&](const json& mesh, const std::string& field) {
        warnOfUnknownInEach(mesh, field, "primitives", kPrimitive, diagnostics);
    });
    warnOfUnknownInEach(document, "", "materials", kMaterial, diagnostics,
                        [&](const json& material, const std::string& field) {
                            warnOfUnknownInMaterial(material, field, diagnostics);
                        });
    warnOfUnknownInEach(document, "", "cameras", kCamera, diagnostics,
                        [&](const json& camera, const std::string& field) {
                            warnOfUnknownIn(camera, field, "orthographic", kOrthographic, diagnostics);
                            warnOfUnknownIn(camera, field, "perspective", kPerspective, diagnostics);
                        });
    warnOfUnknownInEach(document, "", "accessors", kAccessor, diagnostics,
                        [&](const json& accessor, const std::string& field) {
                            warnOfUnknownInAccessor(accessor, field, diagnostics);
                        });
    warnOfUnknownInEach(document, "", "bufferViews", kBufferView, diagnostics);
    warnOfUnknownInEach(document, "", "buffers", kBuffer, diagnostics);
    warnOfUnknownInEach(document, "", "images", kImage, diagnostics);
    warnOfUnknownInEach(document, "", "samplers", kSampler, diagnostics);
    warnOfUnknownInEach(document, "", "textures", kTexture, diagnostics);
    if (const json* lights = extension(document, kPunctualLightsExtension)) {
        const std::string field = extensionField("", kPunctualLightsExtension);
        if (warnOfUnknown(*lights, field, kLightsExtension, diagnostics)) {
            warnOfUnknownInEach(*lights, field, "lights", kLight, diagnostics,
                                [&](const json& light, const std::string& lightField) {
                                    warnOfUnknownIn(light, lightField, "spot", kSpot, diagnostics);
                                });
        }
    }
}

}  // namespace vkdr
