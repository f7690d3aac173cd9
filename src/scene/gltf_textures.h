#pragma once
#include <cstdint>
#include <map>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

inline constexpr const char* kTextureTransformExtension = "KHR_texture_transform";

// sRGB transfer function -> linear, for one channel value in [0, 1].
float srgbToLinear(float encoded);

// Turns the colour textures that materials reference (base colour, emission: both
// sRGB-encoded in glTF) into Scene textures, one per glTF image however many textures
// and materials share it.
class SrgbTextureCache {
public:
    SrgbTextureCache(const tinygltf::Model& model, GltfDiagnostics& diagnostics,
                     std::vector<Texture>& textures)
        : model_(model), diagnostics_(diagnostics), textures_(textures) {}

    // Index into Scene::textures, or -1 when `info` references no texture, and how it
    // is looked up (its sampler's wrap modes and KHR_texture_transform). `field` is the
    // path of `info`, e.g. "materials[0].pbrMetallicRoughness.baseColorTexture".
    struct MappedTexture {
        int32_t texture = -1;
        TextureMapping mapping;
    };
    MappedTexture textureFor(const tinygltf::TextureInfo& info, std::string_view field);

private:
    int32_t decodedImage(int imageIndex);
    TextureWrap wrapOf(int mode, const std::string& samplerField, const char* key) const;
    TextureMapping transformOf(const tinygltf::Value& transform, const std::string& field) const;

    const tinygltf::Model& model_;
    GltfDiagnostics& diagnostics_;
    std::vector<Texture>& textures_;
    std::map<int, int32_t> textureOfImage_;
};

}  // namespace vkdr
