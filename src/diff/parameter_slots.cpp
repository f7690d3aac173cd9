#include "diff/parameter_slots.h"

#include "core/error.h"
#include "device_types.h"
#include "scene/parameters.h"

namespace vkdr {
namespace {

// The middle part of "kind/<name>/property", which may itself contain slashes.
std::string middleName(const std::string& name) {
    size_t first = name.find('/');
    size_t last = name.rfind('/');
    return name.substr(first + 1, last - first - 1);
}

template <typename T>
uint32_t indexByName(const std::vector<T>& items, const std::string& name) {
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) {
            return static_cast<uint32_t>(i);
        }
    }
    return ~0u;
}

// Where a texture starts in the texel array the renderer uploads (textures one after another).
uint32_t firstTexel(const Scene& scene, size_t texture) {
    size_t first = 0;
    for (size_t i = 0; i < texture; ++i) {
        first += scene.textures[i].texels.size();
    }
    return static_cast<uint32_t>(first);
}

}  // namespace

std::vector<ParameterSlot> resolveParameterSlots(const Scene& scene, const std::vector<std::string>& names) {
    std::vector<ParameterSlot> slots;
    for (const std::string& name : names) {
        getParameter(scene, name);  // throws, listing the valid names, if unknown
        std::string owner = middleName(name);
        std::string property = name.substr(name.rfind('/') + 1);
        ParameterSlot slot{name, ParameterSlot::Kind::SigmaA, 0};
        if (name.rfind("media/", 0) == 0) {
            slot.index = indexByName(scene.media, owner);
            slot.kind = property == "sigma_a"   ? ParameterSlot::Kind::SigmaA
                        : property == "sigma_s" ? ParameterSlot::Kind::SigmaS
                                                : ParameterSlot::Kind::PhaseG;
        } else {
            slot.index = indexByName(scene.materials, owner);
            slot.kind = name.rfind("lights/", 0) == 0 ? ParameterSlot::Kind::Emission : ParameterSlot::Kind::BaseColor;
        }
        if (slot.index == ~0u) {
            throw Error("parameter " + name + ": no medium or material named " + owner);
        }
        if (property == "base_color_texture") {
            size_t texture = size_t(scene.materials[slot.index].baseColorTexture);
            slot.kind = ParameterSlot::Kind::BaseColorTexture;
            slot.index = firstTexel(scene, texture);
            slot.texelCount = static_cast<uint32_t>(scene.textures[texture].texels.size());
        }
        slots.push_back(slot);
    }
    return slots;
}

std::vector<double> gatherGradient(const ParameterSlot& slot, const SceneGradients& gradients) {
    auto rgb = [](const std::vector<float>& v, size_t first) {
        return std::vector<double>{v[first], v[first + 1], v[first + 2]};
    };
    const size_t medium = size_t(slot.index) * gpu::kMediumGradientStride;
    switch (slot.kind) {
    case ParameterSlot::Kind::SigmaA: return rgb(gradients.media, medium + gpu::kMediumGradientSigmaA);
    case ParameterSlot::Kind::SigmaS: return rgb(gradients.media, medium + gpu::kMediumGradientSigmaS);
    case ParameterSlot::Kind::PhaseG: return {gradients.media[medium + gpu::kMediumGradientG]};
    case ParameterSlot::Kind::BaseColor: return rgb(gradients.baseColors, size_t(slot.index) * 4);
    case ParameterSlot::Kind::BaseColorTexture: {
        std::vector<double> texels;
        texels.reserve(size_t(slot.texelCount) * 3);
        for (size_t texel = slot.index; texel < size_t(slot.index) + slot.texelCount; ++texel) {
            std::vector<double> value = rgb(gradients.texels, 4 * texel);
            texels.insert(texels.end(), value.begin(), value.end());
        }
        return texels;
    }
    case ParameterSlot::Kind::Emission: return rgb(gradients.emissions, size_t(slot.index) * 4);
    }
    return {};
}

}  // namespace vkdr
