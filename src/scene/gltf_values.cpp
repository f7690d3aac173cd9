#include "scene/gltf_values.h"

#include <cmath>

namespace vkdr {
namespace {

double finiteNumber(const GltfDiagnostics& diagnostics, const tinygltf::Value& value,
                    const std::string& path) {
    if (!value.IsNumber()) {
        diagnostics.fail(path, "expected a number");
    }
    double number = value.GetNumberAsDouble();
    if (std::string problem = floatProblem(number); !problem.empty()) {
        diagnostics.fail(path, problem);
    }
    return number;
}

}  // namespace

std::string floatProblem(double number) {
    if (!std::isfinite(number)) {
        return "must be finite, got " + formatNumber(number);
    }
    if (!std::isfinite(float(number))) {
        return "must be finite, got " + formatNumber(number) + ": beyond float range (magnitude at most 3.4e+38)";
    }
    return "";
}

double readNumber(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                  std::string_view field, const std::string& key, double fallback) {
    if (!object.Has(key)) {
        return fallback;
    }
    return finiteNumber(diagnostics, object.Get(key), member(field, key));
}

glm::vec3 readRgbOrScalar(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                          std::string_view field, const std::string& key, glm::vec3 fallback) {
    if (!object.Has(key)) {
        return fallback;
    }
    const tinygltf::Value& value = object.Get(key);
    std::string path = member(field, key);
    if (value.IsNumber()) {
        return glm::vec3(float(finiteNumber(diagnostics, value, path)));
    }
    if (!value.IsArray() || value.ArrayLen() != 3) {
        diagnostics.fail(path, "expected a number or an array of 3 numbers");
    }
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
        rgb[c] = float(finiteNumber(diagnostics, value.Get(c), indexed(path, size_t(c))));
    }
    return rgb;
}

glm::vec2 readVec2(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                   std::string_view field, const std::string& key, glm::vec2 fallback) {
    if (!object.Has(key)) {
        return fallback;
    }
    const tinygltf::Value& value = object.Get(key);
    std::string path = member(field, key);
    if (!value.IsArray() || value.ArrayLen() != 2) {
        diagnostics.fail(path, "expected an array of 2 numbers");
    }
    return glm::vec2(float(finiteNumber(diagnostics, value.Get(0), indexed(path, 0))),
                     float(finiteNumber(diagnostics, value.Get(1), indexed(path, 1))));
}

std::string readString(const GltfDiagnostics& diagnostics, const tinygltf::Value& object,
                       std::string_view field, const std::string& key,
                       const std::string& fallback) {
    if (!object.Has(key)) {
        return fallback;
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsString()) {
        diagnostics.fail(member(field, key), "expected a string");
    }
    return value.Get<std::string>();
}

glm::vec3 rgbFromFactor(const GltfDiagnostics& diagnostics, const std::vector<double>& factor,
                        std::string_view field) {
    if (factor.size() < 3) {
        diagnostics.fail(field, "expected at least 3 numbers");
    }
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
        if (std::string problem = floatProblem(factor[size_t(c)]); !problem.empty()) {
            diagnostics.fail(indexed(field, size_t(c)), problem);
        }
        rgb[c] = float(factor[size_t(c)]);
    }
    return rgb;
}

}  // namespace vkdr
