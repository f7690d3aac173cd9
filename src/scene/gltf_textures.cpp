#include "scene/gltf_textures.h"

#include <cmath>
#include <cstring>

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

int32_t SrgbTextureCache::textureFor(const tinygltf::TextureInfo& info, std::string_view field) {
    if (info.index < 0) {
        return -1;
    }
    std::string indexField = std::string(field) + ".index";
    if (size_t(info.index) >= model_.textures.size()) {
        diagnostics_.fail(indexField, "texture " + std::to_string(info.index) +
                                          " out of range (" +
                                          std::to_string(model_.textures.size()) + " textures)");
    }
    if (info.texCoord != 0) {
        diagnostics_.warn(std::string(field) + ".texCoord",
                          "only TEXCOORD_0 is read; the texture is looked up with it");
    }
    if (info.extensions.count("KHR_texture_transform")) {
        diagnostics_.warn(field, "KHR_texture_transform is ignored");
    }
    const tinygltf::Texture& texture = model_.textures[size_t(info.index)];
    std::string textureField = indexed("textures", size_t(info.index));
    if (texture.source < 0 || size_t(texture.source) >= model_.images.size()) {
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
        if (sampler.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT ||
            sampler.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT) {
            diagnostics_.warn(indexed("samplers", size_t(texture.sampler)),
                              "only repeat wrapping is supported; textures repeat");
        }
    }
    return decodedImage(texture.source);
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
