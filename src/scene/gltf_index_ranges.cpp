#include "scene/gltf_index_ranges.h"

#include <string>

#include <nlohmann/json.hpp>

#include "scene/gltf_lights.h"

namespace vkdr {
namespace {

using json = nlohmann::json;

class IndexRanges {
public:
    IndexRanges(const json& document, const GltfDiagnostics& diagnostics)
        : document_(document), diagnostics_(diagnostics) {}

    // `object[key]`, where present and a whole number, must index `entries`, whose entries
    // the message calls `singular` (an accessor) and `plural` (accessors).
    void require(const json& object, const std::string& field, const char* key, const json* entries,
                 const char* singular, const char* plural) const {
        if (!object.is_object() || !object.contains(key)) return;
        requireEntry(object[key], field.empty() ? std::string(key) : member(field, key), entries, singular, plural);
    }

    void requireEntry(const json& index, const std::string& field, const json* entries, const char* singular,
                      const char* plural) const {
        if (!index.is_number_integer()) return;
        const size_t count = entries && entries->is_array() ? entries->size() : 0;
        if (index.get<int64_t>() < 0 || size_t(index.get<int64_t>()) >= count) {
            diagnostics_.fail(field, std::string(singular) + " " + index.dump() + " out of range (" +
                                         std::to_string(count) + " " + plural + ")");
        }
    }

    // The document's top-level array `key`, or null where there is none.
    const json* array(const char* key) const {
        return document_.contains(key) && document_[key].is_array() ? &document_[key] : nullptr;
    }

    // f(entry, field) for each entry of the array `object[key]`.
    template <typename F>
    void forEach(const json& object, const std::string& field, const char* key, F f) const {
        if (!object.is_object() || !object.contains(key) || !object[key].is_array()) return;
        const json& entries = object[key];
        const std::string name = field.empty() ? std::string(key) : member(field, key);
        for (size_t i = 0; i < entries.size(); ++i) f(entries[i], indexed(name, i));
    }

    void requireAll() const {
        const json* accessors = array("accessors");
        const json* nodes = array("nodes");
        const json* textures = array("textures");
        require(document_, "", "scene", array("scenes"), "scene", "scenes");
        forEach(document_, "", "scenes", [&](const json& scene, const std::string& field) {
            forEach(scene, field, "nodes", [&](const json& node, const std::string& f) {
                requireEntry(node, f, nodes, "node", "nodes");
            });
        });
        const json* lights = nullptr;
        if (document_.contains("extensions") && document_["extensions"].is_object() &&
            document_["extensions"].contains(kPunctualLightsExtension) &&
            document_["extensions"][kPunctualLightsExtension].is_object() &&
            document_["extensions"][kPunctualLightsExtension].contains("lights")) {
            lights = &document_["extensions"][kPunctualLightsExtension]["lights"];
        }
        forEach(document_, "", "nodes", [&](const json& node, const std::string& field) {
            require(node, field, "mesh", array("meshes"), "mesh", "meshes");
            require(node, field, "camera", array("cameras"), "camera", "cameras");
            require(node, field, "skin", array("skins"), "skin", "skins");
            forEach(node, field, "children", [&](const json& child, const std::string& f) {
                requireEntry(child, f, nodes, "node", "nodes");
            });
            if (node.contains("extensions") && node["extensions"].is_object() &&
                node["extensions"].contains(kPunctualLightsExtension)) {
                require(node["extensions"][kPunctualLightsExtension],
                        member(member(field, "extensions"), kPunctualLightsExtension), "light", lights, "light",
                        "lights");
            }
        });
        forEach(document_, "", "meshes", [&](const json& mesh, const std::string& field) {
            forEach(mesh, field, "primitives", [&](const json& primitive, const std::string& f) {
                require(primitive, f, "indices", accessors, "accessor", "accessors");
                require(primitive, f, "material", array("materials"), "material", "materials");
                if (primitive.contains("attributes") && primitive["attributes"].is_object()) {
                    for (const auto& [name, index] : primitive["attributes"].items()) {
                        requireEntry(index, member(member(f, "attributes"), name), accessors, "accessor", "accessors");
                    }
                }
                forEach(primitive, f, "targets", [&](const json& target, const std::string& t) {
                    if (!target.is_object()) return;
                    for (const auto& [name, index] : target.items()) {
                        requireEntry(index, member(t, name), accessors, "accessor", "accessors");
                    }
                });
            });
        });
        forEach(document_, "", "materials", [&](const json& material, const std::string& field) {
            auto texture = [&](const json& object, const std::string& f, const char* key) {
                if (object.is_object() && object.contains(key)) {
                    require(object[key], member(f, key), "index", textures, "texture", "textures");
                }
            };
            for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) {
                texture(material, field, key);
            }
            if (material.contains("pbrMetallicRoughness")) {
                const std::string pbr = member(field, "pbrMetallicRoughness");
                for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"}) {
                    texture(material["pbrMetallicRoughness"], pbr, key);
                }
            }
        });
        forEach(document_, "", "textures", [&](const json& texture, const std::string& field) {
            require(texture, field, "source", array("images"), "image", "images");
            require(texture, field, "sampler", array("samplers"), "sampler", "samplers");
        });
        forEach(document_, "", "images", [&](const json& image, const std::string& field) {
            require(image, field, "bufferView", array("bufferViews"), "buffer view", "buffer views");
        });
        forEach(document_, "", "accessors", [&](const json& accessor, const std::string& field) {
            require(accessor, field, "bufferView", array("bufferViews"), "buffer view", "buffer views");
        });
        forEach(document_, "", "bufferViews", [&](const json& view, const std::string& field) {
            require(view, field, "buffer", array("buffers"), "buffer", "buffers");
        });
        forEach(document_, "", "skins", [&](const json& skin, const std::string& field) {
            require(skin, field, "inverseBindMatrices", accessors, "accessor", "accessors");
            require(skin, field, "skeleton", nodes, "node", "nodes");
            forEach(skin, field, "joints", [&](const json& joint, const std::string& f) {
                requireEntry(joint, f, nodes, "node", "nodes");
            });
        });
        forEach(document_, "", "animations", [&](const json& animation, const std::string& field) {
            const json* samplers = animation.contains("samplers") ? &animation["samplers"] : nullptr;
            forEach(animation, field, "channels", [&](const json& channel, const std::string& f) {
                require(channel, f, "sampler", samplers, "sampler", "samplers of the animation");
                if (channel.contains("target")) {
                    require(channel["target"], member(f, "target"), "node", nodes, "node", "nodes");
                }
            });
            forEach(animation, field, "samplers", [&](const json& sampler, const std::string& f) {
                require(sampler, f, "input", accessors, "accessor", "accessors");
                require(sampler, f, "output", accessors, "accessor", "accessors");
            });
        });
    }

private:
    const json& document_;
    const GltfDiagnostics& diagnostics_;
};

}  // namespace

void requireIndicesInRange(const json& document, const GltfDiagnostics& diagnostics) {
    IndexRanges(document, diagnostics).requireAll();
}

}  // namespace vkdr
