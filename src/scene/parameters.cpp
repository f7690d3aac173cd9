#include "scene/parameters.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <type_traits>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"

namespace vkdr {
namespace {

enum class Quantity { Sigma, Anisotropy, Albedo, Emission };

// Where a parameter's floats live in the Scene, and what values they accept: `size`
// values, `channels` at a time, consecutive groups `stride` floats apart (a texture's
// texels are RGBA, of which the parameter is the RGB).
template <typename Float>
struct ParameterSlot {
    Float* values = nullptr;
    size_t size = 0;
    Quantity quantity = Quantity::Sigma;
    size_t channels = 1;
    size_t stride = 1;

    Float& operator[](size_t i) const { return values[(i / channels) * stride + i % channels]; }
};

template <typename Float>
ParameterSlot<Float> packedSlot(Float* values, size_t size, Quantity quantity) {
    return {values, size, quantity, size, size};
}

struct ParsedName {
    std::string_view kind;    // "media", "materials" or "lights"
    std::string_view object;  // medium or material name; may itself contain '/'
    std::string_view field;   // "sigma_a", "base_color", ...
};

std::optional<ParsedName> parseName(std::string_view name) {
    size_t first = name.find('/');
    size_t last = name.rfind('/');
    if (first == std::string_view::npos || first == last) {
        return std::nullopt;
    }
    return ParsedName{name.substr(0, first), name.substr(first + 1, last - first - 1),
                      name.substr(last + 1)};
}

template <typename SceneType>
auto findSlot(SceneType& scene, std::string_view name) {
    using Float = std::conditional_t<std::is_const_v<SceneType>, const float, float>;
    std::optional<ParameterSlot<Float>> slot;
    std::optional<ParsedName> parsed = parseName(name);
    if (!parsed) {
        return slot;
    }
    if (parsed->kind == "media") {
        for (auto& medium : scene.media) {
            if (medium.name != parsed->object) {
                continue;
            }
            if (parsed->field == "sigma_a") {
                slot = packedSlot<Float>(glm::value_ptr(medium.sigma_a), 3, Quantity::Sigma);
            } else if (parsed->field == "sigma_s") {
                slot = packedSlot<Float>(glm::value_ptr(medium.sigma_s), 3, Quantity::Sigma);
            } else if (parsed->field == "g") {
                slot = packedSlot<Float>(&medium.g, 1, Quantity::Anisotropy);
            }
        }
        return slot;
    }
    for (auto& material : scene.materials) {
        if (material.name != parsed->object || material.isMediumBoundary()) {
            continue;
        }
        if (parsed->kind == "materials" && parsed->field == "base_color") {
            slot = packedSlot<Float>(glm::value_ptr(material.baseColor), 3, Quantity::Albedo);
        } else if (parsed->kind == "materials" && parsed->field == "base_color_texture" &&
                   material.baseColorTexture >= 0) {
            auto& texels = scene.textures[size_t(material.baseColorTexture)].texels;
            slot = ParameterSlot<Float>{glm::value_ptr(texels.front()), 3 * texels.size(), Quantity::Albedo, 3, 4};
        } else if (parsed->kind == "lights" && parsed->field == "emission") {
            slot = packedSlot<Float>(glm::value_ptr(material.emission), 3, Quantity::Emission);
        }
    }
    return slot;
}

[[noreturn]] void failUnknown(const Scene& scene, std::string_view name) {
    std::string message = "unknown parameter '" + std::string(name) + "'; valid names:";
    for (const std::string& valid : parameterNames(scene)) {
        message += " " + valid;
    }
    throw Error(message);
}

std::string numberText(float value) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, ec == std::errc() ? end : text);
}

// Empty when `value` is acceptable, else why not.
std::string rangeProblem(Quantity quantity, float value) {
    if (!std::isfinite(value)) {
        return "must be finite, got " + numberText(value);
    }
    switch (quantity) {
    case Quantity::Sigma:
    case Quantity::Emission:
        return value >= 0.0f ? "" : "must be >= 0, got " + numberText(value);
    case Quantity::Anisotropy:
        return std::abs(value) < 1.0f ? "" : "|g| must be < 1, got " + numberText(value);
    case Quantity::Albedo:
        return value >= 0.0f && value <= 1.0f ? "" : "must be in [0, 1], got " + numberText(value);
    }
    return "";
}

}  // namespace

std::vector<std::string> parameterNames(const Scene& scene) {
    std::vector<std::string> names;
    for (const Medium& medium : scene.media) {
        for (const char* field : {"sigma_a", "sigma_s", "g"}) {
            names.push_back("media/" + medium.name + "/" + field);
        }
    }
    for (const Material& material : scene.materials) {
        if (!material.isMediumBoundary()) {
            names.push_back("materials/" + material.name + "/base_color");
            if (material.baseColorTexture >= 0) {
                names.push_back("materials/" + material.name + "/base_color_texture");
            }
        }
    }
    for (const Material& material : scene.materials) {
        if (!material.isMediumBoundary() && material.isEmissive()) {
            names.push_back("lights/" + material.name + "/emission");
        }
    }
    return names;
}

std::vector<float> getParameter(const Scene& scene, std::string_view name) {
    auto slot = findSlot(scene, name);
    if (!slot) {
        failUnknown(scene, name);
    }
    std::vector<float> values(slot->size);
    for (size_t i = 0; i < slot->size; ++i) {
        values[i] = (*slot)[i];
    }
    return values;
}

void setParameter(Scene& scene, std::string_view name, std::span<const float> values) {
    auto slot = findSlot(scene, name);
    if (!slot) {
        failUnknown(scene, name);
    }
    if (values.size() != slot->size && values.size() != 1) {
        throw Error("parameter " + std::string(name) + ": expected " +
                    (slot->size == 1 ? std::string("1 value") : "1 or " + std::to_string(slot->size) + " values") +
                    ", got " + std::to_string(values.size()));
    }
    for (float value : values) {
        if (std::string problem = rangeProblem(slot->quantity, value); !problem.empty()) {
            throw Error("parameter " + std::string(name) + ": " + problem);
        }
    }
    for (size_t i = 0; i < slot->size; ++i) {
        (*slot)[i] = values.size() == 1 ? values[0] : values[i];
    }
}

void applyAssignment(Scene& scene, std::string_view assignment) {
    auto fail = [&](const std::string& problem) -> void {
        throw Error("assignment '" + std::string(assignment) + "': " + problem);
    };
    size_t equals = assignment.find('=');
    if (equals == std::string_view::npos || equals == 0) {
        fail("expected NAME=VALUE or NAME=VALUE,VALUE,VALUE");
    }
    std::string_view name = assignment.substr(0, equals);
    std::string_view list = assignment.substr(equals + 1);
    std::vector<float> values;
    while (true) {
        size_t comma = list.find(',');
        std::string_view text = list.substr(0, comma);
        float value = 0.0f;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
            fail("'" + std::string(text) + "' is not a number");
        }
        values.push_back(value);
        if (comma == std::string_view::npos) {
            break;
        }
        list.remove_prefix(comma + 1);
    }
    setParameter(scene, name, values);
}

}  // namespace vkdr
