#include "scene/parameters.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <optional>
#include <type_traits>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/signed_decimal.h"
#include "scene/parameter_kinds.h"

namespace vkdr {
namespace {

// Where a parameter's floats are stored in the Scene: `size` values, `channels` at a
// time, consecutive groups `stride` floats apart (a texture's texels are RGBA, of which
// the parameter is the RGB).
template <typename Float>
struct ParameterStorage {
    Float* values = nullptr;
    size_t size = 0;
    const ParameterDescription* description = nullptr;
    size_t stride = 1;

    Float& operator[](size_t i) const {
        const size_t channels = description->channels;
        return values[(i / channels) * stride + i % channels];
    }

    // Values stored back to back (no texel's fourth channel between them), which a grid's
    // millions of voxels are: they copy in one go instead of one index at a time.
    bool isContiguous() const { return stride == description->channels; }
};

template <typename Float>
ParameterStorage<Float> packedStorage(Float* values, ParameterKind kind) {
    const ParameterDescription& description = describe(kind);
    return {values, description.channels, &description, description.channels};
}

template <typename Float, typename MediumType>
ParameterStorage<Float> mediumStorage(MediumType& medium, ParameterKind kind) {
    switch (kind) {
    case ParameterKind::SigmaA: return packedStorage<Float>(glm::value_ptr(medium.sigma_a), kind);
    case ParameterKind::SigmaS: return packedStorage<Float>(glm::value_ptr(medium.sigma_s), kind);
    case ParameterKind::G: return packedStorage<Float>(&medium.g, kind);
    case ParameterKind::MediumEmission: return packedStorage<Float>(glm::value_ptr(medium.emission), kind);
    default: throw Error("a medium has no parameter of this kind");
    }
}

template <typename SceneType>
auto findStorage(SceneType& scene, std::string_view name) {
    using Float = std::conditional_t<std::is_const_v<SceneType>, const float, float>;
    std::optional<ParameterStorage<Float>> storage;
    std::optional<ParsedParameterName> parsed = parseParameterName(name);
    if (!parsed) {
        return storage;
    }
    const ParameterKind kind = parsed->description->kind;
    if (parsed->description->owner == ParameterOwner::Medium) {
        for (auto& medium : scene.media) {
            if (medium.name != parsed->owner) {
                continue;
            }
            if (!isGridKind(kind)) {
                storage = mediumStorage<Float>(medium, kind);
            } else if (int32_t grid = mediumGridOf(medium, kind); grid >= 0) {
                auto& values = scene.densityGrids[size_t(grid)].grid.values;
                storage = ParameterStorage<Float>{values.data(), values.size(), parsed->description,
                                                  parsed->description->channels};
            }
        }
        return storage;
    }
    if (parsed->description->owner == ParameterOwner::PunctualLight) {
        for (auto& light : scene.punctualLights) {
            if (light.name == parsed->owner) {
                storage = packedStorage<Float>(glm::value_ptr(light.intensity), kind);
            }
        }
        return storage;
    }
    for (auto& material : scene.materials) {
        if (material.name != parsed->owner || material.isMediumBoundary()) {
            continue;
        }
        if (kind == ParameterKind::BaseColor) {
            storage = packedStorage<Float>(glm::value_ptr(material.baseColor), kind);
        } else if (kind == ParameterKind::BaseColorTexture && material.baseColorTexture >= 0) {
            auto& texels = scene.textures[size_t(material.baseColorTexture)].texels;
            const size_t size = parsed->description->channels * texels.size();
            storage = ParameterStorage<Float>{glm::value_ptr(texels.front()), size, parsed->description,
                                              size_t(glm::vec4::length())};
        } else if (kind == ParameterKind::Emission && material.emitter) {
            storage = packedStorage<Float>(glm::value_ptr(material.emission), kind);
        }
    }
    return storage;
}

[[noreturn]] void failUnknown(const Scene& scene, std::string_view name) {
    std::string message = "unknown parameter '" + std::string(name) + "'; valid names:";
    for (const std::string& valid : parameterNames(scene)) {
        message += " " + valid;
    }
    throw Error(message);
}

}  // namespace

std::vector<std::string> parameterNames(const Scene& scene) {
    std::vector<std::string> names;
    for (const Medium& medium : scene.media) {
        for (ParameterKind kind : {ParameterKind::SigmaA, ParameterKind::SigmaS, ParameterKind::G}) {
            names.push_back(parameterName(kind, medium.name));
        }
        if (medium.isHeterogeneous()) {
            names.push_back(parameterName(ParameterKind::Density, medium.name));
        }
        names.push_back(parameterName(ParameterKind::MediumEmission, medium.name));
        if (medium.hasEmissionGrid()) {
            names.push_back(parameterName(ParameterKind::EmissionGrid, medium.name));
        }
        if (medium.hasAlbedoGrid()) {
            names.push_back(parameterName(ParameterKind::AlbedoGrid, medium.name));
        }
    }
    for (const Material& material : scene.materials) {
        if (!material.isMediumBoundary()) {
            names.push_back(parameterName(ParameterKind::BaseColor, material.name));
            if (material.baseColorTexture >= 0) {
                names.push_back(parameterName(ParameterKind::BaseColorTexture, material.name));
            }
        }
    }
    for (const Material& material : scene.materials) {
        if (!material.isMediumBoundary() && material.emitter) {
            names.push_back(parameterName(ParameterKind::Emission, material.name));
        }
    }
    for (const PunctualLight& light : scene.punctualLights) {
        names.push_back(parameterName(ParameterKind::LightIntensity, light.name));
    }
    return names;
}

std::vector<float> getParameter(const Scene& scene, std::string_view name) {
    auto storage = findStorage(scene, name);
    if (!storage) {
        failUnknown(scene, name);
    }
    if (storage->isContiguous()) {
        return std::vector<float>(storage->values, storage->values + storage->size);
    }
    std::vector<float> values(storage->size);
    for (size_t i = 0; i < storage->size; ++i) {
        values[i] = (*storage)[i];
    }
    return values;
}

const float* parameterStorageAddress(const Scene& scene, std::string_view name) {
    auto storage = findStorage(scene, name);
    if (!storage) {
        failUnknown(scene, name);
    }
    return storage->values;
}

void setParameter(Scene& scene, std::string_view name, std::span<const float> values) {
    auto storage = findStorage(scene, name);
    if (!storage) {
        failUnknown(scene, name);
    }
    if (values.size() != storage->size && values.size() != 1) {
        throw Error("parameter " + std::string(name) + ": expected " +
                    (storage->size == 1 ? std::string("1 value") : "1 or " + std::to_string(storage->size) + " values") +
                    ", got " + std::to_string(values.size()));
    }
    const ValueRange& range = storage->description->range;
    auto invalid = std::find_if(values.begin(), values.end(),
                                [&](float value) { return !std::isfinite(value) || !range.contains(value); });
    if (invalid != values.end()) {
        throw Error("parameter " + std::string(name) + ": " + whichValue(size_t(invalid - values.begin()), values.size()) +
                    valueProblem(*storage->description, *invalid));
    }
    if (values.size() == storage->size && storage->isContiguous()) {
        std::copy(values.begin(), values.end(), storage->values);
        return;
    }
    for (size_t i = 0; i < storage->size; ++i) {
        (*storage)[i] = values.size() == 1 ? values[0] : values[i];
    }
}

std::string whichValue(size_t index, size_t count) {
    if (count == 1) return "";
    return "value " + std::to_string(index) + " of " + std::to_string(count) + " (counted from 0): ";
}

namespace {

struct ParsedAssignment {
    std::string_view name;
    std::vector<float> values;
};

ParsedAssignment parseAssignment(std::string_view assignment) {
    auto fail = [&](const std::string& problem) -> void {
        throw Error("assignment '" + std::string(assignment) + "': " + problem);
    };
    const std::string_view name = assignedName(assignment);
    if (name.empty()) {
        fail("expected NAME=VALUE or NAME=VALUE,VALUE,VALUE");
    }
    ParsedAssignment parsed{name, {}};
    std::string_view list = assignment.substr(name.size() + 1);
    while (true) {
        size_t comma = list.find(',');
        std::string_view text = list.substr(0, comma);
        const std::string_view number = withoutPlusSign(text);
        float value = 0.0f;
        auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
        if (text.empty() || end != number.data() + number.size() ||
            (ec != std::errc() && ec != std::errc::result_out_of_range)) {
            fail("'" + std::string(text) + "' is not a number");
        }
        if (ec == std::errc::result_out_of_range) {
            fail("'" + std::string(text) + "' is out of float range (magnitudes from 1.4e-45 to 3.4e+38, or 0)");
        }
        parsed.values.push_back(value);
        if (comma == std::string_view::npos) {
            break;
        }
        list.remove_prefix(comma + 1);
    }
    return parsed;
}

}  // namespace

std::string_view assignedName(std::string_view assignment) {
    // The last '=': values hold none, while a material's or medium's name may.
    const size_t equals = assignment.rfind('=');
    return equals == std::string_view::npos ? std::string_view() : assignment.substr(0, equals);
}

void applyAssignment(Scene& scene, std::string_view assignment) {
    ParsedAssignment parsed = parseAssignment(assignment);
    setParameter(scene, parsed.name, parsed.values);
}

std::string canonicalAssignment(std::string_view assignment) {
    ParsedAssignment parsed = parseAssignment(assignment);
    std::vector<std::string> numbers;
    for (float value : parsed.values) {
        char number[32];
        auto [end, ec] = std::to_chars(number, number + sizeof(number), value);
        numbers.emplace_back(number, end);
    }
    // One value sets every element of a parameter, so a list of one value repeated sets
    // what that value alone does (the same bits: "-0" and "0" differ).
    if (std::adjacent_find(numbers.begin(), numbers.end(), std::not_equal_to<>()) == numbers.end()) {
        numbers.resize(1);
    }
    std::string text = std::string(parsed.name) + "=";
    for (size_t i = 0; i < numbers.size(); ++i) text += (i == 0 ? "" : ",") + numbers[i];
    return text;
}

int32_t mediumGridOf(const Medium& medium, ParameterKind kind) {
    switch (kind) {
    case ParameterKind::Density: return medium.densityGrid;
    case ParameterKind::EmissionGrid: return medium.emissionGrid;
    case ParameterKind::AlbedoGrid: return medium.albedoGrid;
    default: return -1;
    }
}

int32_t gridIndexOf(const Scene& scene, std::string_view name) {
    const std::optional<ParsedParameterName> parsed = parseParameterName(name);
    if (!parsed || !isGridKind(parsed->description->kind)) return -1;
    for (const Medium& medium : scene.media) {
        if (medium.name == parsed->owner) {
            return mediumGridOf(medium, parsed->description->kind);
        }
    }
    return -1;
}

const DensityGrid* densityGridOf(const Scene& scene, std::string_view name) {
    const int32_t grid = gridIndexOf(scene, name);
    return grid < 0 ? nullptr : &scene.densityGrids[size_t(grid)].grid;
}

}  // namespace vkdr
