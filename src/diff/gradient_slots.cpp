#include "diff/gradient_slots.h"

#include "core/error.h"
#include "device_types.h"
#include "scene/parameters.h"

namespace vkdr {
namespace {

template <typename T>
size_t indexByName(const std::vector<T>& items, std::string_view name, const std::string& parameter) {
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) {
            return i;
        }
    }
    throw Error("parameter " + parameter + ": no medium or material named " + std::string(name));
}

// Where a texture starts in the texel array the renderer uploads (textures one after another).
size_t firstTexel(const Scene& scene, size_t texture) {
    size_t first = 0;
    for (size_t i = 0; i < texture; ++i) {
        first += scene.textures[i].texels.size();
    }
    return first;
}

// Where a medium's gradient of this kind sits among its kMediumGradientStride floats.
size_t mediumOffset(MediumGradient gradient) {
    switch (gradient) {
    case MediumGradient::SigmaA: return gpu::kMediumGradientSigmaA;
    case MediumGradient::SigmaS: return gpu::kMediumGradientSigmaS;
    case MediumGradient::G: return gpu::kMediumGradientG;
    case MediumGradient::None: break;
    }
    throw Error("a parameter that is not a medium's has no medium gradient");
}

// Base colours, emissions and texels accumulate 4 floats each, of which the parameter is the RGB.
constexpr size_t kColorStride = 4;

GradientSlot resolveGradientSlot(const Scene& scene, const std::string& name) {
    const ParsedParameterName parsed = *parseParameterName(name);
    const ParameterDescription& description = *parsed.description;
    GradientSlot slot{name, description.kind, nullptr};
    const size_t owner = description.owner == ParameterOwner::Medium
                             ? indexByName(scene.media, parsed.owner, name)
                             : indexByName(scene.materials, parsed.owner, name);
    switch (description.accumulator) {
    case GradientAccumulator::Medium:
        slot.accumulator = &SceneGradients::media;
        slot.first = owner * gpu::kMediumGradientStride + mediumOffset(description.mediumGradient);
        break;
    case GradientAccumulator::BaseColor:
        slot.accumulator = &SceneGradients::baseColors;
        slot.first = owner * kColorStride;
        break;
    case GradientAccumulator::Emission:
        slot.accumulator = &SceneGradients::emissions;
        slot.first = owner * kColorStride;
        break;
    case GradientAccumulator::Texel: {
        const size_t texture = size_t(scene.materials[owner].baseColorTexture);
        slot.accumulator = &SceneGradients::texels;
        slot.first = firstTexel(scene, texture) * kColorStride;
        slot.groups = scene.textures[texture].texels.size();
        slot.stride = kColorStride;
        break;
    }
    }
    return slot;
}

}  // namespace

std::vector<GradientSlot> resolveGradientSlots(const Scene& scene, const std::vector<std::string>& names) {
    std::vector<GradientSlot> slots;
    for (const std::string& name : names) {
        getParameter(scene, name);  // throws, listing the valid names, if unknown
        slots.push_back(resolveGradientSlot(scene, name));
    }
    return slots;
}

std::vector<double> gatherGradient(const GradientSlot& slot, const SceneGradients& gradients) {
    const std::vector<float>& accumulator = gradients.*slot.accumulator;
    const size_t channels = describe(slot.kind).channels;
    std::vector<double> gradient;
    gradient.reserve(slot.groups * channels);
    for (size_t group = 0; group < slot.groups; ++group) {
        for (size_t c = 0; c < channels; ++c) {
            gradient.push_back(accumulator[slot.first + group * slot.stride + c]);
        }
    }
    return gradient;
}

}  // namespace vkdr
