#include "diff/gradient_slots.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "device_types.h"
#include "scene/parameters.h"

namespace vkdr {

bool hasSigmaSGradient(const Medium& medium) {
    return !medium.isHeterogeneous() || glm::all(glm::greaterThan(medium.sigma_s, glm::vec3(0.0f)));
}

namespace {

template <typename T>
size_t indexByName(const std::vector<T>& items, std::string_view name, const std::string& parameter) {
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) {
            return i;
        }
    }
    throw Error("parameter " + parameter + ": no medium, material or light named " + std::string(name));
}

// Where a texture starts in the texel array the renderer uploads (textures one after another).
size_t firstTexel(const Scene& scene, size_t texture) {
    size_t first = 0;
    for (size_t i = 0; i < texture; ++i) {
        first += scene.textures[i].texels.size();
    }
    return first;
}

// The SceneGradients vector of each accumulator, in the order of gpu::GradientAccumulator.
#define VKDR_SCENE_GRADIENTS_MEMBER(name, field, ...) &SceneGradients::field,
constexpr std::vector<float> SceneGradients::*kSceneGradients[] = {
    VKDR_GRADIENT_ACCUMULATORS(VKDR_SCENE_GRADIENTS_MEMBER)};
#undef VKDR_SCENE_GRADIENTS_MEMBER

GradientSlot resolveGradientSlot(const Scene& scene, const std::string& name) {
    const ParsedParameterName parsed = *parseParameterName(name);
    const ParameterDescription& description = *parsed.description;
    const size_t owner = description.owner == ParameterOwner::Medium     ? indexByName(scene.media, parsed.owner, name)
                         : description.owner == ParameterOwner::Material ? indexByName(scene.materials, parsed.owner, name)
                                                                         : indexByName(scene.punctualLights, parsed.owner, name);
    if (description.kind == ParameterKind::SigmaS && !hasSigmaSGradient(scene.media[owner])) {
        throw Error("parameter " + name + ": the gradient of a density grid medium's sigma_s is not available "
                    "where a channel of it is 0 (light it would scatter is not sampled); start it above 0");
    }
    const size_t sumsPerItem = gpu::layoutOf(description.accumulator).sumsPerItem;
    GradientSlot slot{name, description.kind, kSceneGradients[size_t(description.accumulator)]};
    if (description.accumulator == gpu::GradientAccumulator::texelGradients) {
        // A texture's parameter is every texel of it, each an item of its own.
        const size_t texture = size_t(scene.materials[owner].baseColorTexture);
        slot.first = firstTexel(scene, texture) * sumsPerItem + description.firstFloat;
        slot.groups = scene.textures[texture].texels.size();
        slot.stride = sumsPerItem;
    } else if (description.accumulator == gpu::GradientAccumulator::densityGradients) {
        // A grid's parameter is every voxel of it (its channels one after another), after
        // the values of the grids before it.
        const size_t grid = size_t(mediumGridOf(scene.media[owner], description.kind));
        if (scene.densityGrids[grid].grid.voxelCount() == 0) {
            throw Error("parameter " + name + ": the grid '" + scene.densityGrids[grid].grid.name + "' in " +
                        scene.densityGrids[grid].file.filename().string() +
                        " has no active voxels, so there are no values to differentiate or fit");
        }
        for (size_t i = 0; i < grid; ++i) {
            slot.first += scene.densityGrids[i].grid.values.size() * sumsPerItem;
        }
        slot.groups = scene.densityGrids[grid].grid.voxelCount();
        slot.stride = sumsPerItem * description.channels;
    } else {
        slot.first = owner * sumsPerItem + description.firstFloat;
    }
    return slot;
}

}  // namespace

std::vector<GradientSlot> resolveGradientSlots(const Scene& scene, const std::vector<std::string>& names) {
    std::vector<GradientSlot> slots;
    for (const std::string& name : names) {
        if (std::count(names.begin(), names.end(), name) > 1) {
            throw Error("parameter '" + name + "' is given twice");
        }
        getParameter(scene, name);  // throws, listing the valid names, if unknown
        GradientSlot slot = resolveGradientSlot(scene, name);
        // Each name would get the whole gradient, and a fit would step the values once
        // for each.
        for (const GradientSlot& other : slots) {
            if (other.accumulator == slot.accumulator && other.first == slot.first) {
                throw Error("parameters '" + other.name + "' and '" + name +
                            "' name the same values (a texture or grid that both use); give one of them");
            }
        }
        slots.push_back(std::move(slot));
    }
    return slots;
}

std::vector<double> gatherGradient(const GradientSlot& slot, const SceneGradients& gradients) {
    std::vector<double> gradient(slot.valueCount(), 0.0);
    addWeightedGradient(slot, gradients, 1.0, gradient);
    return gradient;
}

void addWeightedGradient(const GradientSlot& slot, const SceneGradients& gradients, double weight,
                         std::span<double> sum) {
    const std::vector<float>& accumulator = gradients.*slot.accumulator;
    const size_t channels = describe(slot.kind).channels;
    if (sum.size() != slot.valueCount()) {
        throw std::logic_error("addWeightedGradient: " + slot.name + " has " + std::to_string(slot.valueCount()) +
                               " values, the sum " + std::to_string(sum.size()));
    }
    tbb::parallel_for(size_t(0), slot.groups, [&](size_t group) {
        for (size_t c = 0; c < channels; ++c) {
            sum[group * channels + c] += weight * double(accumulator[slot.first + group * slot.stride + c]);
        }
    });
}

DerivativeTargets derivativeTargetsOf(const std::vector<GradientSlot>& slots) {
    DerivativeTargets targets = DerivativeTargets::of({});
    for (const GradientSlot& slot : slots) {
        targets.want(slot.kind);
    }
    return targets;
}

}  // namespace vkdr
