#include "scene/gltf_lights.h"

#include <cmath>
#include <numbers>
#include <set>
#include <span>

#include "scene/gltf_values.h"
#include "scene/parameter_kinds.h"
#include "scene/unique_name.h"

namespace vkdr {
namespace {

std::string lightField(size_t index) {
    return indexed(std::string("extensions.") + kPunctualLightsExtension + ".lights", index);
}

PunctualLight::Type lightType(const tinygltf::Light& source, const std::string& field,
                              const GltfDiagnostics& diagnostics) {
    if (source.type == "point") return PunctualLight::Type::Point;
    if (source.type == "spot") return PunctualLight::Type::Spot;
    if (source.type == "directional") return PunctualLight::Type::Directional;
    diagnostics.fail(field + ".type", "expected \"point\", \"spot\" or \"directional\", got \"" + source.type + "\"");
}

glm::vec3 lightIntensity(const tinygltf::Light& source, const std::string& field, const GltfDiagnostics& diagnostics) {
    glm::vec3 color(1.0f);
    if (!source.color.empty()) {
        if (source.color.size() != 3) {
            diagnostics.fail(field + ".color", "expected 3 numbers, got " + std::to_string(source.color.size()));
        }
        color = rgbFromFactor(diagnostics, source.color, field + ".color");
        for (int c = 0; c < 3; ++c) {
            if (color[c] < 0.0f) {
                diagnostics.fail(indexed(field + ".color", size_t(c)), "must be >= 0, got " + formatNumber(color[c]));
            }
        }
    }
    if (!(std::isfinite(source.intensity) && source.intensity >= 0.0)) {
        diagnostics.fail(field + ".intensity", "must be a finite number >= 0, got " + formatNumber(source.intensity));
    }
    // Multiplied in double: an intensity beyond float's range times a colour of 0 is a dark
    // light, and times any other colour is named as too bright, not as NaN.
    const ParameterDescription& description = describe(ParameterKind::LightIntensity);
    glm::vec3 intensity(0.0f);
    for (int c = 0; c < 3; ++c) {
        const double product = double(color[c]) * source.intensity;
        if (!(product <= description.range.upper)) {
            diagnostics.fail(field, "color x intensity must be in [" + formatNumber(description.range.lower) + ", " +
                                        formatNumber(description.range.upper) + "], got " + formatNumber(product));
        }
        intensity[c] = float(product);
        if (std::string problem = valueProblem(description, intensity[c]); !problem.empty()) {
            diagnostics.fail(field, "color x intensity " + problem);
        }
    }
    return intensity;
}

void readSpotCones(const tinygltf::Light& source, const std::string& field, const GltfDiagnostics& diagnostics,
                   PunctualLight& light) {
    double inner = source.spot.innerConeAngle;
    double outer = source.spot.outerConeAngle;
    if (!(std::isfinite(outer) && outer > 0.0 && outer <= std::numbers::pi / 2)) {
        diagnostics.fail(field + ".spot.outerConeAngle", "must be in (0, pi/2], got " + formatNumber(outer));
    }
    if (!(std::isfinite(inner) && inner >= 0.0 && inner < outer)) {
        diagnostics.fail(field + ".spot.innerConeAngle",
                         "must be in [0, outerConeAngle = " + formatNumber(outer) + "), got " + formatNumber(inner));
    }
    light.cosInnerCone = float(std::cos(inner));
    light.cosOuterCone = float(std::cos(outer));
}

}  // namespace

std::vector<PunctualLight> readPunctualLights(const tinygltf::Model& model, GltfDiagnostics& diagnostics) {
    // An unnamed light is named `lights[i]`, followed by '_' as often as it takes to
    // differ from every light's own name (a light may be named "lights[1]").
    std::set<std::string> taken;
    for (const tinygltf::Light& source : model.lights) taken.insert(source.name);
    std::vector<PunctualLight> lights;
    for (size_t i = 0; i < model.lights.size(); ++i) {
        const tinygltf::Light& source = model.lights[i];
        const std::string field = lightField(i);
        PunctualLight light;
        light.name = source.name;
        if (light.name.empty()) {
            light.name = firstFreeName(indexed("lights", i), [&](const std::string& n) { return taken.count(n) > 0; });
            taken.insert(light.name);
            if (light.name != indexed("lights", i)) {
                diagnostics.warn(field, "unnamed, and '" + indexed("lights", i) +
                                            "' is another light's name; this one is named '" + light.name + "'");
            }
        }
        light.type = lightType(source, field, diagnostics);
        light.intensity = lightIntensity(source, field, diagnostics);
        if (light.type == PunctualLight::Type::Spot) {
            readSpotCones(source, field, diagnostics, light);
        }
        for (size_t j = 0; j < lights.size(); ++j) {
            if (lights[j].name == light.name) {
                diagnostics.fail(field + ".name", "'" + light.name + "' already names " + lightField(j) +
                                                      "; light names must be unique");
            }
        }
        lights.push_back(std::move(light));
    }
    return lights;
}

std::optional<LightPlacement> placeNodeLight(const tinygltf::Model& model, size_t nodeIndex,
                                             const glm::mat4& nodeToWorld, const GltfDiagnostics& diagnostics) {
    const tinygltf::Node& node = model.nodes[nodeIndex];
    auto extension = node.extensions.find(kPunctualLightsExtension);
    if (extension == node.extensions.end()) {
        return std::nullopt;
    }
    const std::string field = indexed("nodes", nodeIndex) + ".extensions." + kPunctualLightsExtension;
    if (!extension->second.IsObject()) {
        diagnostics.fail(field, "expected an object");
    }
    if (!extension->second.Has("light")) {
        diagnostics.fail(field, "has no \"light\": the index of the light the node places");
    }
    double index = readNumber(diagnostics, extension->second, field, "light", -1.0);
    if (!(index >= 0.0 && index < double(model.lights.size()) && index == std::floor(index))) {
        diagnostics.fail(field + ".light", "expected the index of one of the " + std::to_string(model.lights.size()) +
                                               " lights, got " + formatNumber(index));
    }
    LightPlacement placement;
    placement.light = uint32_t(index);
    placement.position = glm::vec3(nodeToWorld[3]);
    placement.direction = glm::normalize(-glm::vec3(nodeToWorld[2]));
    const glm::vec3& p = placement.position;
    const glm::vec3& d = placement.direction;
    if (!(std::isfinite(p.x + p.y + p.z) && std::isfinite(d.x + d.y + d.z))) {
        diagnostics.fail(indexed("nodes", nodeIndex), "the light's transform is degenerate (a zero scale) or not finite");
    }
    return placement;
}

}  // namespace vkdr
