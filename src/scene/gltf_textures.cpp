#include "scene/gltf_textures.h"

#include <cmath>
#include <cstring>

#include "scene/gltf_values.h"

namespace vkdr {
namespace {

// Channel i of texel `texel`, scaled to [0, 1], for 8- and 16-bit images.
float channel(const tinygltf::Image& image, size_t texel, int i) {
    size_t offset = texel * size_t(image.component) + size_t(i);
    if (image.bits == 16) {
        uint16_t value;
        std::memcpy(&value, image.image.data() + offset * 2, sizeof(value));
        return float(value) / 65535.0f;
    }
    return float(image.image[offset]) / 255.0f;
}

std::string textureName(const tinygltf::Image& image, int imageIndex) {
    if (!image.name.empty()) {
        return image.name;
    }
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
        return image.uri;
    }
    return indexed("images", size_t(imageIndex));
}

}  // namespace

float srgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f
                               : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

SrgbTextureCache::MappedTexture SrgbTextureCache::textureFor(const tinygltf::TextureInfo& info,
                                                              std::string_view field) {
    MappedTexture mapped;
    if (info.index < 0) {
        return mapped;
    }
    std::string indexField = std::string(field) + ".index";
    if (size_t(info.index) >= model_.textures.size()) {
        diagnostics_.fail(indexField, "texture " + std::to_string(info.index) +
                                          " out of range (" +
                                          std::to_string(model_.textures.size()) + " textures)");
    }
    // Which TEXCOORD set the texture looks up decides its primitives' uvs
    // (materialTextureCoordinateSet).
    if (auto transform = info.extensions.find(kTextureTransformExtension); transform != info.extensions.end()) {
        mapped.mapping =
            transformOf(transform->second, std::string(field) + ".extensions." + kTextureTransformExtension);
    }
    const tinygltf::Texture& texture = model_.textures[size_t(info.index)];
    std::string textureField = indexed("textures", size_t(info.index));
    if (texture.source < 0) {
        // tinygltf reads an absent source as -1; glTF leaves it to extensions (WebP, KTX2).
        diagnostics_.fail(textureField, "has no source image (images of extensions such as EXT_texture_webp are not "
                                        "read); give it \"source\": the index of a PNG, JPEG or BMP image");
    }
    if (size_t(texture.source) >= model_.images.size()) {
        diagnostics_.fail(textureField + ".source",
                          "image " + std::to_string(texture.source) + " out of range (" +
                              std::to_string(model_.images.size()) + " images)");
    }
    if (texture.sampler >= 0) {
        if (size_t(texture.sampler) >= model_.samplers.size()) {
            diagnostics_.fail(textureField + ".sampler",
                              "sampler " + std::to_string(texture.sampler) + " out of range (" +
                                  std::to_string(model_.samplers.size()) + " samplers)");
        }
        const tinygltf::Sampler& sampler = model_.samplers[size_t(texture.sampler)];
        std::string samplerField = indexed("samplers", size_t(texture.sampler));
        mapped.mapping.wrapS = wrapOf(sampler.wrapS, samplerField, "wrapS");
        mapped.mapping.wrapT = wrapOf(sampler.wrapT, samplerField, "wrapT");
        if (sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) {
            diagnostics_.warn(member(samplerField, "magFilter"),
                              "NEAREST (9728) is not supported; the texture is looked up bilinearly");
        }
    }
    mapped.texture = decodedImage(texture.source);
    return mapped;
}

TextureWrap SrgbTextureCache::wrapOf(int mode, const std::string& samplerField, const char* key) const {
    switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
        default:
            diagnostics_.fail(member(samplerField, key),
                              "must be 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497 (REPEAT), got " +
                                  std::to_string(mode));
    }
}

// KHR_texture_transform: uv' = translation(offset) * rotation * scale * uv, where the
// rotation takes (u, v) to (cos r u + sin r v, -sin r u + cos r v): counter-clockwise in
// texture space, whose v runs down (glTF issue 1563; as Blender, Babylon.js and Khronos'
// sample viewer and TextureTransformTest model have it; the GLSL in the extension's text
// turns the other way).
TextureMapping SrgbTextureCache::transformOf(const tinygltf::Value& transform, const std::string& field) const {
    if (!transform.IsObject()) {
        diagnostics_.fail(field, "expected an object");
    }
    const glm::vec2 offset = readVec2(diagnostics_, transform, field, "offset", glm::vec2(0.0f));
    const double rotation = readNumber(diagnostics_, transform, field, "rotation", 0.0);
    const glm::vec2 scale = readVec2(diagnostics_, transform, field, "scale", glm::vec2(1.0f));
    const float c = float(std::cos(rotation)), s = float(std::sin(rotation));
    TextureMapping mapping;
    mapping.uRow = glm::vec3(c * scale.x, s * scale.y, offset.x);
    mapping.vRow = glm::vec3(-s * scale.x, c * scale.y, offset.y);
    return mapping;
}

int32_t SrgbTextureCache::decodedImage(int imageIndex) {
    if (auto found = textureOfImage_.find(imageIndex); found != textureOfImage_.end()) {
        return found->second;
    }
    const tinygltf::Image& image = model_.images[size_t(imageIndex)];
    std::string field = indexed("images", size_t(imageIndex));
    bool validLayout = image.width > 0 && image.height > 0 && image.component >= 1 &&
                       image.component <= 4 && (image.bits == 8 || image.bits == 16);
    size_t texelCount = validLayout ? size_t(image.width) * size_t(image.height) : 0;
    if (!validLayout ||
        image.image.size() < texelCount * size_t(image.component) * size_t(image.bits / 8)) {
        diagnostics_.fail(field, "image could not be decoded");
    }

    Texture texture;
    texture.name = textureName(image, imageIndex);
    texture.width = image.width;
    texture.height = image.height;
    texture.texels.resize(texelCount);
    // Grey images (1-2 channels) repeat the grey value in RGB; the last channel of a
    // 2- or 4-channel image is alpha, which is linear already.
    bool hasAlpha = image.component == 2 || image.component == 4;
    int colorChannels = image.component - (hasAlpha ? 1 : 0);
    for (size_t t = 0; t < texelCount; ++t) {
        glm::vec4 texel(1.0f);
        for (int c = 0; c < 3; ++c) {
            texel[c] = srgbToLinear(channel(image, t, colorChannels == 1 ? 0 : c));
        }
        if (hasAlpha) {
            texel.a = channel(image, t, image.component - 1);
        }
        texture.texels[t] = texel;
    }
    textures_.push_back(std::move(texture));
    int32_t index = int32_t(textures_.size() - 1);
    textureOfImage_[imageIndex] = index;
    return index;
}

}  // namespace vkdr
