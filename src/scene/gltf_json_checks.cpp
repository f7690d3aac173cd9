#include "scene/gltf_json_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <regex>
#include <span>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "scene/gltf_lights.h"
#include "scene/gltf_media.h"
#include "scene/gltf_textures.h"
#include "scene/gltf_values.h"
#include "scene/scene_file_access.h"

namespace vkdr {
namespace {

using nlohmann::json;

constexpr std::array<std::string_view, 8> kUnderstoodExtensions = {
    "KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_volume",            kTextureTransformExtension,   kPunctualLightsExtension,
    kMediumExtension,                  kBackgroundExtension};

// The members of vkdiffrender's own extensions; "extensions" and "extras" are allowed on
// every glTF object.
constexpr std::array<std::string_view, 10> kSceneMediumMembers = {
    "name", "sigma_a", "sigma_s", "g", "emission", "density", "emissionGrid", "albedoGrid", "extensions", "extras"};
constexpr std::array<std::string_view, 5> kGridReferenceMembers = {"uri", "grid", "node", "extensions", "extras"};
constexpr std::array<std::string_view, 3> kBackgroundMembers = {"radiance", "extensions", "extras"};
constexpr std::array<std::string_view, 3> kGridReferences = {"density", "emissionGrid", "albedoGrid"};
constexpr std::array<std::string_view, 6> kTextureTransformMembers = {"offset",   "rotation",   "scale",
                                                                      "texCoord", "extensions", "extras"};

// A rotation whose length is further than this from 1 is not an exporter's rounding.
constexpr double kUnitQuaternionTolerance = 1e-3;

std::string describeValue(const json& value) {
    std::string text = value.dump();
    return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

// tinygltf reads a member of the wrong JSON type as absent, so its default would silently
// take its place ("doubleSided": "true" is false): the members the loader reads are
// checked for their type.
enum class JsonKind { Object, Array, String, Number, Boolean };

struct MemberKind {
    std::string_view key;
    JsonKind kind;
};

constexpr std::array<MemberKind, 14> kDocumentMembers = {{{"asset", JsonKind::Object},
                                                          {"extensionsUsed", JsonKind::Array},
                                                          {"extensionsRequired", JsonKind::Array},
                                                          {"scenes", JsonKind::Array},
                                                          {"nodes", JsonKind::Array},
                                                          {"meshes", JsonKind::Array},
                                                          {"materials", JsonKind::Array},
                                                          {"cameras", JsonKind::Array},
                                                          {"accessors", JsonKind::Array},
                                                          {"bufferViews", JsonKind::Array},
                                                          {"buffers", JsonKind::Array},
                                                          {"textures", JsonKind::Array},
                                                          {"images", JsonKind::Array},
                                                          {"samplers", JsonKind::Array}}};
constexpr std::array<MemberKind, 2> kSceneMembers = {{{"name", JsonKind::String}, {"nodes", JsonKind::Array}}};
constexpr std::array<MemberKind, 1> kNamedMembers = {{{"name", JsonKind::String}}};
// tinygltf reads a uri that is not text as none: a GLB's buffer would take the BIN chunk.
constexpr std::array<MemberKind, 2> kFileMembers = {{{"name", JsonKind::String}, {"uri", JsonKind::String}}};
constexpr std::array<MemberKind, 2> kPrimitiveMembers = {{{"attributes", JsonKind::Object},
                                                          {"targets", JsonKind::Array}}};
constexpr std::array<MemberKind, 7> kMaterialMembers = {{{"name", JsonKind::String},
                                                         {"pbrMetallicRoughness", JsonKind::Object},
                                                         {"doubleSided", JsonKind::Boolean},
                                                         {"alphaMode", JsonKind::String},
                                                         {"emissiveTexture", JsonKind::Object},
                                                         {"normalTexture", JsonKind::Object},
                                                         {"occlusionTexture", JsonKind::Object}}};
constexpr std::array<MemberKind, 2> kPbrMembers = {{{"baseColorTexture", JsonKind::Object},
                                                    {"metallicRoughnessTexture", JsonKind::Object}}};
constexpr std::array<MemberKind, 4> kCameraMembers = {{{"name", JsonKind::String},
                                                       {"type", JsonKind::String},
                                                       {"perspective", JsonKind::Object},
                                                       {"orthographic", JsonKind::Object}}};
constexpr std::array<MemberKind, 2> kOrthographicMembers = {{{"znear", JsonKind::Number},
                                                             {"zfar", JsonKind::Number}}};
constexpr std::array<MemberKind, 3> kAccessorMembers = {{{"componentType", JsonKind::Number},
                                                         {"type", JsonKind::String},
                                                         {"normalized", JsonKind::Boolean}}};
constexpr std::array<MemberKind, 4> kLightMembers = {{{"name", JsonKind::String},
                                                      {"type", JsonKind::String},
                                                      {"intensity", JsonKind::Number},
                                                      {"spot", JsonKind::Object}}};
constexpr std::array<MemberKind, 2> kSpotMembers = {{{"innerConeAngle", JsonKind::Number},
                                                     {"outerConeAngle", JsonKind::Number}}};

bool isKind(const json& value, JsonKind kind) {
    switch (kind) {
    case JsonKind::Object: return value.is_object();
    case JsonKind::Array: return value.is_array();
    case JsonKind::String: return value.is_string();
    case JsonKind::Number: return value.is_number();
    case JsonKind::Boolean: return value.is_boolean();
    }
    return false;
}

const char* kindName(JsonKind kind) {
    switch (kind) {
    case JsonKind::Object: return "an object";
    case JsonKind::Array: return "an array";
    case JsonKind::String: return "a string";
    case JsonKind::Number: return "a number";
    case JsonKind::Boolean: return "true or false";
    }
    return "";
}

void requireKind(const json& value, const std::string& field, JsonKind kind, const GltfDiagnostics& diagnostics) {
    if (!isKind(value, kind)) {
        diagnostics.fail(field, std::string("expected ") + kindName(kind) + ", got " + describeValue(value));
    }
}

void requireMemberKinds(const json& object, const std::string& field, std::span<const MemberKind> members,
                        const GltfDiagnostics& diagnostics) {
    for (const auto& [key, kind] : members) {
        const std::string name(key);
        if (!object.contains(name)) continue;
        requireKind(object[name], field.empty() ? name : member(field, name), kind, diagnostics);
    }
}

// Every entry of the array `object[key]` must be of `kind`: tinygltf skips the others,
// and the later entries' indices would shift.
void requireEntryKinds(const json& object, const std::string& field, const std::string& key, JsonKind kind,
                       const GltfDiagnostics& diagnostics) {
    if (!object.contains(key) || !object[key].is_array()) return;
    const std::string arrayField = field.empty() ? key : member(field, key);
    for (size_t i = 0; i < object[key].size(); ++i) {
        requireKind(object[key][i], indexed(arrayField, i), kind, diagnostics);
    }
}

// Nulls are dropped by tinygltf wherever they stand, so the default silently takes their
// place. Skipped: "extras" (anything goes there) and extensions the loader does not read.
void refuseNulls(const json& value, const std::string& field, const GltfDiagnostics& diagnostics) {
    if (value.is_null()) {
        diagnostics.fail(field, "null is not a glTF value; leave the member out for its default");
    }
    if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) refuseNulls(value[i], indexed(field, i), diagnostics);
        return;
    }
    if (!value.is_object()) return;
    for (const auto& [key, child] : value.items()) {
        const std::string childField = field.empty() ? key : member(field, key);
        if (key == "extras") continue;
        if (key == "extensions" && child.is_object()) {
            for (const auto& [name, extension] : child.items()) {
                if (isUnderstoodExtension(name)) refuseNulls(extension, member(childField, name), diagnostics);
            }
            continue;
        }
        refuseNulls(child, childField, diagnostics);
    }
}

// tinygltf skips an extension whose value is not an object.
void requireObjectExtensions(const json& object, const std::string& field, const GltfDiagnostics& diagnostics) {
    if (!object.is_object() || !object.contains("extensions")) return;
    const json& extensions = object["extensions"];
    const std::string extensionsField = field.empty() ? "extensions" : member(field, "extensions");
    if (!extensions.is_object()) diagnostics.fail(extensionsField, "expected an object");
    for (const auto& [name, extension] : extensions.items()) {
        if (isUnderstoodExtension(name) && !extension.is_object()) {
            diagnostics.fail(member(extensionsField, name), "expected an object, got " + describeValue(extension));
        }
    }
}

// Checks the members of one of vkdiffrender's extension objects: an empty {} or [] would
// be dropped (and the default used); an unknown member would be ignored.
void checkOwnMembers(const json& object, const std::string& field, std::span<const std::string_view> known,
                     GltfDiagnostics& diagnostics) {
    for (const auto& [key, value] : object.items()) {
        if (key == "extras" || key == "extensions") continue;
        if ((value.is_object() || value.is_array()) && value.empty()) {
            diagnostics.fail(member(field, key), "is empty (" + value.dump() + "); give a value or leave it out");
        }
        if (std::find(known.begin(), known.end(), key) == known.end()) {
            std::string names;
            for (std::string_view name : known) {
                if (name != "extensions" && name != "extras") names += (names.empty() ? "" : ", ") + std::string(name);
            }
            diagnostics.warn(member(field, key), "unknown member, ignored (known: " + names + ")");
        }
    }
}

void requireNumbers(const json& object, const std::string& field, const std::string& key, size_t count,
                    const GltfDiagnostics& diagnostics) {
    if (!object.contains(key)) return;
    const json& value = object[key];
    bool numbers = value.is_array() && value.size() == count &&
                   std::all_of(value.begin(), value.end(), [](const json& entry) { return entry.is_number(); });
    if (!numbers) {
        diagnostics.fail(member(field, key), "expected an array of " + std::to_string(count) + " numbers, got " +
                                                 describeValue(value));
    }
}

// tinygltf reads an integer member only where the JSON writes it as an integer (1, not
// 1.0), and casts indices, modes and wrap modes to int: anything else gives the member's
// default, or a wrapped value. Byte offsets it reads as 64-bit.
constexpr int64_t kLargestInt = std::numeric_limits<int32_t>::max();

bool isWholeNumber(const json& value, int64_t most = kLargestInt) {
    return value.is_number_integer() && value.get<int64_t>() >= 0 && value.get<int64_t>() <= most;
}

std::string wholeNumberUpTo(int64_t most) {
    return "an integer from 0 to " + std::to_string(most) + ", without a decimal point";
}

void requireIndex(const json& value, const std::string& field, const GltfDiagnostics& diagnostics) {
    if (!isWholeNumber(value)) {
        diagnostics.fail(field, "expected an index (" + wholeNumberUpTo(kLargestInt) + "), got " + describeValue(value));
    }
}

void requireIndexMember(const json& object, const std::string& field, const std::string& key,
                        const GltfDiagnostics& diagnostics) {
    if (object.contains(key)) requireIndex(object[key], member(field, key), diagnostics);
}

void checkMedium(const json& extensions, const std::string& extensionsField, bool sceneWide,
                 GltfDiagnostics& diagnostics) {
    if (!extensions.is_object() || !extensions.contains(kMediumExtension)) return;
    const json& medium = extensions[kMediumExtension];
    const std::string field = member(extensionsField, kMediumExtension);
    // A material's medium takes the material's name.
    std::span<const std::string_view> known(kSceneMediumMembers);
    checkOwnMembers(medium, field, sceneWide ? known : known.subspan(1), diagnostics);
    for (std::string_view reference : kGridReferences) {
        const std::string key(reference);
        if (medium.contains(key) && medium[key].is_object()) {
            checkOwnMembers(medium[key], member(field, key), kGridReferenceMembers, diagnostics);
            requireIndexMember(medium[key], member(field, key), "node", diagnostics);
        }
    }
}

// A byte offset, a primitive's mode or a sampler's wrap mode, which tinygltf reads as its
// default where it is negative, fractional or text: geometry from the wrong bytes, drawn
// in the wrong mode, or a texture repeated where it should be clamped.
void requireWholeNumberMember(const json& object, const std::string& field, const std::string& key,
                              const GltfDiagnostics& diagnostics, int64_t most = kLargestInt) {
    if (object.contains(key) && !isWholeNumber(object[key], most)) {
        diagnostics.fail(member(field, key), "expected " + wholeNumberUpTo(most) + ", got " + describeValue(object[key]));
    }
}

// glTF's bounds on a buffer view's stride, which tinygltf words as if 4 did not divide 252.
void checkByteStride(const json& view, const std::string& field, const GltfDiagnostics& diagnostics) {
    if (!view.contains("byteStride")) return;
    const json& stride = view["byteStride"];
    if (!isWholeNumber(stride) || stride.get<double>() < 4.0 || stride.get<double>() > 252.0 ||
        std::fmod(stride.get<double>(), 4.0) != 0.0) {
        diagnostics.fail(member(field, "byteStride"),
                         "must be a multiple of 4 from 4 to 252, got " + describeValue(stride));
    }
}

// A number the loader needs above `bound`; absent is allowed where the schema allows it.
void requireAbove(const json& object, const std::string& field, const std::string& key, double bound,
                  const std::string& boundName, const GltfDiagnostics& diagnostics) {
    if (!object.contains(key)) return;
    const json& value = object[key];
    if (!value.is_number() || !(value.get<double>() > bound)) {
        diagnostics.fail(member(field, key), "must be a number > " + boundName + ", got " + describeValue(value));
    }
}

// Node transforms are applied as floats: an entry beyond float's range would make the
// vertices below the node infinite, and the mesh would take the blame.
void requireFloatEntries(const json& object, const std::string& field, const char* key,
                         const GltfDiagnostics& diagnostics) {
    if (!object.contains(key)) return;
    for (size_t i = 0; i < object[key].size(); ++i) {
        if (std::string problem = floatProblem(object[key][i].get<double>()); !problem.empty()) {
            diagnostics.fail(indexed(member(field, key), i), problem);
        }
    }
}

void checkNode(const json& node, const std::string& field, const GltfDiagnostics& diagnostics) {
    requireNumbers(node, field, "matrix", 16, diagnostics);
    requireNumbers(node, field, "translation", 3, diagnostics);
    requireNumbers(node, field, "rotation", 4, diagnostics);
    requireNumbers(node, field, "scale", 3, diagnostics);
    for (const char* key : {"matrix", "translation", "scale"}) requireFloatEntries(node, field, key, diagnostics);
    for (const char* key : {"mesh", "camera", "skin"}) requireIndexMember(node, field, key, diagnostics);
    if (node.contains("extensions") && node["extensions"].is_object() &&
        node["extensions"].contains(kPunctualLightsExtension) &&
        node["extensions"][kPunctualLightsExtension].is_object()) {
        requireIndexMember(node["extensions"][kPunctualLightsExtension],
                           member(member(field, "extensions"), kPunctualLightsExtension), "light", diagnostics);
    }
    if (node.contains("children")) {
        if (!node["children"].is_array()) diagnostics.fail(member(field, "children"), "expected an array of indices");
        for (size_t c = 0; c < node["children"].size(); ++c) {
            requireIndex(node["children"][c], indexed(member(field, "children"), c), diagnostics);
        }
    }
    if (node.contains("matrix")) {
        // Column-major: the last row is entries 3, 7, 11 and 15.
        const json& matrix = node["matrix"];
        if (matrix[3] != 0.0 || matrix[7] != 0.0 || matrix[11] != 0.0 || matrix[15] != 1.0) {
            diagnostics.fail(member(field, "matrix"), "must be affine: its last row (entries 3, 7, 11, 15) "
                                                      "must be 0 0 0 1, got " +
                                                          describeValue(matrix[3]) + " " + describeValue(matrix[7]) +
                                                          " " + describeValue(matrix[11]) + " " +
                                                          describeValue(matrix[15]));
        }
        // The glTF specification forbids both; a reader would use one and drop the other.
        for (const char* key : {"translation", "rotation", "scale"}) {
            if (node.contains(key)) {
                diagnostics.fail(member(field, key), "a node with a matrix must not have a translation, rotation "
                                                     "or scale as well");
            }
        }
    }
    if (node.contains("rotation")) {
        double lengthSquared = 0.0;
        for (const json& entry : node["rotation"]) lengthSquared += entry.get<double>() * entry.get<double>();
        const double length = std::sqrt(lengthSquared);
        if (!(std::abs(length - 1.0) <= kUnitQuaternionTolerance)) {
            diagnostics.fail(member(field, "rotation"), "must be a unit quaternion (x, y, z, w), got length " +
                                                            formatNumber(length));
        }
    }
}

void checkCamera(const json& camera, const std::string& field, const GltfDiagnostics& diagnostics) {
    requireMemberKinds(camera, field, kCameraMembers, diagnostics);
    if (camera.contains("orthographic")) {
        requireMemberKinds(camera["orthographic"], member(field, "orthographic"), kOrthographicMembers, diagnostics);
    }
    if (camera.contains("perspective") && camera["perspective"].is_object()) {
        const json& perspective = camera["perspective"];
        const std::string perspectiveField = member(field, "perspective");
        requireAbove(perspective, perspectiveField, "aspectRatio", 0.0, "0", diagnostics);
        requireAbove(perspective, perspectiveField, "yfov", 0.0, "0", diagnostics);
        requireAbove(perspective, perspectiveField, "znear", 0.0, "0", diagnostics);
        if (perspective.contains("znear")) {
            const double znear = perspective["znear"].get<double>();
            requireAbove(perspective, perspectiveField, "zfar", znear, "znear (" + formatNumber(znear) + ")",
                         diagnostics);
        }
    }
    // An orthographic camera's znear may be 0; tinygltf requires all four members.
    if (camera.contains("orthographic") && camera["orthographic"].is_object()) {
        const json& orthographic = camera["orthographic"];
        const std::string orthographicField = member(field, "orthographic");
        requireAbove(orthographic, orthographicField, "xmag", 0.0, "0", diagnostics);
        requireAbove(orthographic, orthographicField, "ymag", 0.0, "0", diagnostics);
        if (orthographic.contains("znear") && orthographic["znear"].is_number()) {
            const double znear = orthographic["znear"].get<double>();
            if (!(znear >= 0.0)) {
                diagnostics.fail(member(orthographicField, "znear"), "must be >= 0, got " + formatNumber(znear));
            }
            requireAbove(orthographic, orthographicField, "zfar", znear, "znear (" + formatNumber(znear) + ")",
                         diagnostics);
        }
    }
}

// A texture reference (`baseColorTexture` and the like) in `object`: its `index` and
// `texCoord`, and its KHR_texture_transform, whose empty or misspelt members tinygltf
// would drop for their defaults.
void checkTextureReference(const json& object, const std::string& field, const char* key,
                           GltfDiagnostics& diagnostics) {
    if (!object.contains(key) || !object[key].is_object()) return;
    const json& reference = object[key];
    const std::string referenceField = member(field, key);
    requireIndexMember(reference, referenceField, "index", diagnostics);
    requireIndexMember(reference, referenceField, "texCoord", diagnostics);
    requireObjectExtensions(reference, referenceField, diagnostics);
    if (!reference.contains("extensions") || !reference["extensions"].contains(kTextureTransformExtension)) return;
    const json& transform = reference["extensions"][kTextureTransformExtension];
    const std::string transformField = member(member(referenceField, "extensions"), kTextureTransformExtension);
    checkOwnMembers(transform, transformField, kTextureTransformMembers, diagnostics);
    requireNumbers(transform, transformField, "offset", 2, diagnostics);
    requireNumbers(transform, transformField, "scale", 2, diagnostics);
    if (transform.contains("rotation") && !transform["rotation"].is_number()) {
        diagnostics.fail(member(transformField, "rotation"), "expected a number, got " +
                                                                 describeValue(transform["rotation"]));
    }
    requireIndexMember(transform, transformField, "texCoord", diagnostics);
}

void checkMaterial(const json& material, const std::string& field, GltfDiagnostics& diagnostics) {
    requireMemberKinds(material, field, kMaterialMembers, diagnostics);
    requireNumbers(material, field, "emissiveFactor", 3, diagnostics);
    if (material.contains("pbrMetallicRoughness")) {
        const json& pbr = material["pbrMetallicRoughness"];
        const std::string pbrField = member(field, "pbrMetallicRoughness");
        requireMemberKinds(pbr, pbrField, kPbrMembers, diagnostics);
        requireNumbers(pbr, pbrField, "baseColorFactor", 4, diagnostics);
        for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"}) {
            checkTextureReference(pbr, pbrField, key, diagnostics);
        }
    }
    for (const char* key : {"emissiveTexture", "normalTexture", "occlusionTexture"}) {
        checkTextureReference(material, field, key, diagnostics);
    }
    requireObjectExtensions(material, field, diagnostics);
    if (material.contains("extensions")) {
        checkMedium(material["extensions"], member(field, "extensions"), false, diagnostics);
    }
}

// glTF requires a primitive's attributes; without POSITION there is nothing to draw.
void checkPrimitiveMembers(const json& primitive, const std::string& field, const GltfDiagnostics& diagnostics) {
    requireKind(primitive, field, JsonKind::Object, diagnostics);
    requireMemberKinds(primitive, field, kPrimitiveMembers, diagnostics);
    for (const char* key : {"indices", "material"}) requireIndexMember(primitive, field, key, diagnostics);
    requireWholeNumberMember(primitive, field, "mode", diagnostics);
    if (!primitive.contains("attributes")) diagnostics.fail(member(field, "attributes"), "missing; glTF requires it");
    for (const auto& [name, accessor] : primitive["attributes"].items()) {
        requireIndex(accessor, member(member(field, "attributes"), name), diagnostics);
    }
    if (!primitive["attributes"].contains("POSITION")) {
        diagnostics.fail(member(field, "attributes"), "no POSITION attribute");
    }
}

void checkPunctualLights(const json& extension, GltfDiagnostics& diagnostics) {
    const std::string lightsField = member(member("extensions", kPunctualLightsExtension), "lights");
    if (!extension.contains("lights")) return;
    requireKind(extension["lights"], lightsField, JsonKind::Array, diagnostics);
    for (size_t i = 0; i < extension["lights"].size(); ++i) {
        const json& light = extension["lights"][i];
        const std::string field = indexed(lightsField, i);
        requireKind(light, field, JsonKind::Object, diagnostics);
        requireMemberKinds(light, field, kLightMembers, diagnostics);
        requireNumbers(light, field, "color", 3, diagnostics);
        if (light.contains("spot")) requireMemberKinds(light["spot"], member(field, "spot"), kSpotMembers, diagnostics);
        if (light.value("type", json()) == "spot" && !light.contains("spot")) {
            diagnostics.fail(field, "a light of type \"spot\" needs a \"spot\" object, as KHR_lights_punctual asks "
                                    "(its cone angles; {} for the defaults)");
        }
        // Here, where a range written as 0 (not allowed by glTF, and ignored too) differs
        // from none: tinygltf reads an absent one as 0.
        if (light.contains("range")) {
            diagnostics.warn(member(field, "range"), "ignored: a light's intensity falls off with the inverse square "
                                                     "of distance, with no cut-off");
        }
    }
}

// tinygltf's own message for a data URI that does not decode to byteLength bytes quotes
// the whole URI, which may be megabytes long.
void checkDataUriBuffer(const json& buffer, const std::string& field, const GltfDiagnostics& diagnostics) {
    if (!buffer.contains("uri") || !buffer["uri"].is_string()) return;
    const std::string& uri = buffer["uri"].get_ref<const std::string&>();
    const size_t comma = uri.find(',');
    if (!isDataUri(uri) || comma == std::string::npos || uri.rfind(";base64", comma) != comma - 7) return;
    const std::string_view payload = std::string_view(uri).substr(comma + 1);
    const size_t bad = payload.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=");
    if (payload.empty()) diagnostics.fail(member(field, "uri"), "the data URI holds no data");
    if (bad != std::string_view::npos || payload.size() % 4 != 0) {
        diagnostics.fail(member(field, "uri"), "the data URI's base64 text " +
                                                   (bad != std::string_view::npos
                                                        ? "has '" + std::string(1, payload[bad]) + "' at character " +
                                                              std::to_string(bad + 1)
                                                        : "is " + std::to_string(payload.size()) +
                                                              " characters, not a whole number of 4-character groups"));
    }
    const size_t padding = payload.size() - (payload.find_last_not_of('=') + 1);
    const size_t bytes = payload.size() / 4 * 3 - std::min<size_t>(padding, 2);
    if (buffer.contains("byteLength") && buffer["byteLength"].is_number() &&
        buffer["byteLength"].get<double>() != double(bytes)) {
        diagnostics.fail(member(field, "byteLength"), describeValue(buffer["byteLength"]) +
                                                          ", but the data URI holds " + std::to_string(bytes) +
                                                          " bytes");
    }
}

// The version in `asset`'s member `key`, "<major>.<minor>" as the schema writes it, or
// nothing where it is absent.
std::optional<std::pair<int, int>> assetVersion(const json& asset, const char* key,
                                                const GltfDiagnostics& diagnostics) {
    if (!asset.contains(key)) return std::nullopt;
    static const std::regex pattern(R"(([0-9]{1,9})\.([0-9]{1,9}))");
    std::smatch match;
    if (!asset[key].is_string() || !std::regex_match(asset[key].get_ref<const std::string&>(), match, pattern)) {
        diagnostics.fail(member("asset", key), "expected a version such as \"2.0\", got " + describeValue(asset[key]));
    }
    return std::pair(std::stoi(match[1]), std::stoi(match[2]));
}

// The loader implements glTF 2.0. It reads any 2.x file, since minor versions add only
// what a 2.0 reader may ignore, unless the file's minVersion asks for more.
void checkAssetVersion(const json& document, const GltfDiagnostics& diagnostics) {
    if (!document.contains("asset") || !document["asset"].is_object()) return;
    const json& asset = document["asset"];
    if (auto version = assetVersion(asset, "version", diagnostics); version && version->first != 2) {
        diagnostics.fail("asset.version", "glTF " + asset["version"].get<std::string>() +
                                              " is not supported; the loader reads glTF 2.x");
    }
    if (auto minVersion = assetVersion(asset, "minVersion", diagnostics); minVersion && *minVersion > std::pair(2, 0)) {
        diagnostics.fail("asset.minVersion", "the file needs a glTF " + asset["minVersion"].get<std::string>() +
                                                 " reader; the loader implements glTF 2.0");
    }
}

// The document's own members: the lists of extension names hold strings, the other
// top-level arrays objects.
void checkDocumentMembers(const json& document, const GltfDiagnostics& diagnostics) {
    requireMemberKinds(document, "", kDocumentMembers, diagnostics);
    for (const auto& [key, kind] : kDocumentMembers) {
        if (kind != JsonKind::Array) continue;
        const JsonKind entries = key.starts_with("extensions") ? JsonKind::String : JsonKind::Object;
        requireEntryKinds(document, "", std::string(key), entries, diagnostics);
    }
}

// Calls `check` on each object of the top-level array `name`.
template <typename Check>
void forEachEntry(const json& document, const char* name, Check check) {
    if (!document.contains(name) || !document[name].is_array()) return;
    for (size_t i = 0; i < document[name].size(); ++i) {
        if (document[name][i].is_object()) check(document[name][i], indexed(name, i));
    }
}

}  // namespace

bool isUnderstoodExtension(std::string_view extension) {
    return std::find(kUnderstoodExtensions.begin(), kUnderstoodExtensions.end(), extension) !=
           kUnderstoodExtensions.end();
}

void requireWellFormedJson(const json& document, GltfDiagnostics& diagnostics) {
    refuseNulls(document, "", diagnostics);
    checkDocumentMembers(document, diagnostics);
    checkAssetVersion(document, diagnostics);
    requireObjectExtensions(document, "", diagnostics);
    if (document.contains("extensions")) {
        const json& extensions = document["extensions"];
        checkMedium(extensions, "extensions", true, diagnostics);
        if (extensions.contains(kBackgroundExtension)) {
            checkOwnMembers(extensions[kBackgroundExtension], member("extensions", kBackgroundExtension),
                            kBackgroundMembers, diagnostics);
        }
        if (extensions.contains(kPunctualLightsExtension)) {
            checkPunctualLights(extensions[kPunctualLightsExtension], diagnostics);
        }
    }
    forEachEntry(document, "nodes", [&](const json& node, const std::string& field) {
        requireMemberKinds(node, field, kNamedMembers, diagnostics);
        checkNode(node, field, diagnostics);
        requireObjectExtensions(node, field, diagnostics);
    });
    forEachEntry(document, "cameras",
                 [&](const json& camera, const std::string& field) { checkCamera(camera, field, diagnostics); });
    forEachEntry(document, "materials",
                 [&](const json& material, const std::string& field) { checkMaterial(material, field, diagnostics); });
    forEachEntry(document, "samplers", [&](const json& sampler, const std::string& field) {
        for (const char* key : {"wrapS", "wrapT", "magFilter", "minFilter"}) {
            requireWholeNumberMember(sampler, field, key, diagnostics);
        }
    });
    forEachEntry(document, "buffers", [&](const json& buffer, const std::string& field) {
        requireMemberKinds(buffer, field, kFileMembers, diagnostics);
        checkDataUriBuffer(buffer, field, diagnostics);
    });
    forEachEntry(document, "images", [&](const json& image, const std::string& field) {
        requireMemberKinds(image, field, kFileMembers, diagnostics);
    });
    forEachEntry(document, "meshes", [&](const json& mesh, const std::string& field) {
        requireMemberKinds(mesh, field, kNamedMembers, diagnostics);
        if (!mesh.contains("primitives") || !mesh["primitives"].is_array() || mesh["primitives"].empty()) {
            diagnostics.fail(member(field, "primitives"), "a mesh needs an array of at least one primitive");
        }
        for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
            checkPrimitiveMembers(mesh["primitives"][p], indexed(member(field, "primitives"), p), diagnostics);
        }
    });
    // tinygltf reads an index that is negative, fractional or text as "none" (a
    // primitive's -1 material as the default material) or as a wrong one.
    if (document.contains("scene")) requireIndex(document["scene"], "scene", diagnostics);
    // glTF's minimum; with none listed a reader would have to guess which nodes to show.
    if (document.contains("scenes") && document["scenes"].is_array() && document["scenes"].empty()) {
        diagnostics.fail("scenes", "an empty array: list at least one scene, or leave \"scenes\" out");
    }
    forEachEntry(document, "scenes", [&](const json& scene, const std::string& field) {
        requireMemberKinds(scene, field, kSceneMembers, diagnostics);
        if (!scene.contains("nodes")) return;
        for (size_t n = 0; n < scene["nodes"].size(); ++n) {
            requireIndex(scene["nodes"][n], indexed(member(field, "nodes"), n), diagnostics);
        }
    });
    forEachEntry(document, "accessors", [&](const json& accessor, const std::string& field) {
        requireMemberKinds(accessor, field, kAccessorMembers, diagnostics);
        requireIndexMember(accessor, field, "bufferView", diagnostics);
        requireWholeNumberMember(accessor, field, "byteOffset", diagnostics, std::numeric_limits<int64_t>::max());
        // glTF's minimum; a primitive reading none would be dropped without a word.
        requireAbove(accessor, field, "count", 0.0, "0", diagnostics);
    });
    forEachEntry(document, "bufferViews", [&](const json& view, const std::string& field) {
        requireIndexMember(view, field, "buffer", diagnostics);
        requireWholeNumberMember(view, field, "byteOffset", diagnostics, std::numeric_limits<int64_t>::max());
        checkByteStride(view, field, diagnostics);
    });
    forEachEntry(document, "textures", [&](const json& texture, const std::string& field) {
        for (const char* key : {"source", "sampler"}) requireIndexMember(texture, field, key, diagnostics);
    });
}

}  // namespace vkdr
