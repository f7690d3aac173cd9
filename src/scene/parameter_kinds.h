#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "device_types.h"

namespace vkdr {

// Every kind of named scene parameter (scene/parameters.h), described once: setting
// values, the optimiser's bounds, grad --check's steps and the gradient read-back all
// follow from this table. The shaders know the kinds by the same numbers.
enum class ParameterKind : uint32_t {
    SigmaA = gpu::kGradientKindSigmaA,  // media/<medium>/sigma_a: absorption, RGB, per scene unit
    SigmaS = gpu::kGradientKindSigmaS,  // media/<medium>/sigma_s: scattering, RGB, per scene unit
    G = gpu::kGradientKindG,            // media/<medium>/g: Henyey-Greenstein anisotropy
    BaseColor = gpu::kGradientKindBaseColor,  // materials/<material>/base_color: RGB albedo
    // materials/<material>/base_color_texture: the same, per texel
    BaseColorTexture = gpu::kGradientKindBaseColorTexture,
    Emission = gpu::kGradientKindEmission,  // lights/<material>/emission: RGB radiance, at most kMaxRadiance
    // lights/<light>/intensity: a punctual light's RGB color x intensity
    LightIntensity = gpu::kGradientKindLightIntensity,
    // media/<medium>/density: every voxel of a density grid medium's grid, one value each
    Density = gpu::kGradientKindDensity,
    // media/<medium>/emission: RGB radiance emitted per scene unit (per unit density in a
    // density grid medium), at most kMaxRadiance
    MediumEmission = gpu::kGradientKindMediumEmission,
    // media/<medium>/emission_grid: every voxel of a medium's emission grid (the strength
    // that multiplies its emission), one value each
    EmissionGrid = gpu::kGradientKindEmissionGrid,
    // media/<medium>/albedo_grid: every voxel of a medium's albedo grid, RGB each
    AlbedoGrid = gpu::kGradientKindAlbedoGrid,
};

// Whether a kind's parameter is every voxel of one of the scene's grids.
constexpr bool isGridKind(ParameterKind kind) {
    return kind == ParameterKind::Density || kind == ParameterKind::EmissionGrid || kind == ParameterKind::AlbedoGrid;
}

// Whether it is every voxel of a grid of one value per voxel (what the grid priors and
// coarse-to-fine fitting work on).
constexpr bool isScalarGridKind(ParameterKind kind) {
    return kind == ParameterKind::Density || kind == ParameterKind::EmissionGrid;
}

// The largest radiance, per channel, an emitter (emissiveFactor x emissiveStrength, or
// lights/<material>/emission) or the background may have: brighter ones could make a
// pixel, or the loss that squares it, overflow float (parameter_kinds.cpp derives it).
inline constexpr double kMaxRadiance = 1e12;

// The most scattering vertices a path may have (--max-depth); kMaxRadiance counts on it.
inline constexpr uint32_t kMaxScatteringVertices = 100000;

// What the middle of a parameter's name names.
enum class ParameterOwner { Medium, Material, PunctualLight };

// The closed interval a parameter's values must lie in, both when set and while optimised.
struct ValueRange {
    double lower;
    double upper;

    // Compared in float, the precision the scene stores: the float nearest 0.99 lies
    // above the double 0.99, and a value the optimiser projects onto an end of the
    // range must be accepted when it is written back.
    bool contains(float value) const;
};

struct ParameterDescription {
    ParameterKind kind;
    std::string_view prefix;  // the name up to the owner: "media/"
    std::string_view field;   // the name after the owner: "/sigma_a"
    ParameterOwner owner;
    size_t channels;          // floats per value: 3 (RGB, per texel for a texture), 1 for g and per voxel
    ValueRange range;
    // grad --check's central-difference step at `value` (parameter_kinds.cpp says why
    // each kind steps as it does).
    double (*finiteDifferenceStep)(float value);
    // Where the gradient sits: which of the adjoint pass's accumulators
    // (VKDR_GRADIENT_ACCUMULATORS), and its first float within the owner's (or for a
    // texture, each texel's) floats there.
    gpu::GradientAccumulator accumulator;
    uint32_t firstFloat;
};

// The kinds, in the order parameterNames lists a medium's or a material's parameters.
std::span<const ParameterDescription> parameterDescriptions();

const ParameterDescription& describe(ParameterKind kind);

// "media/<medium>/sigma_a" for ParameterKind::SigmaA, as the user spells the pattern.
std::string parameterPattern(const ParameterDescription& description);

// The name of `owner`'s parameter of this kind: parameterName(SigmaA, "fog") is "media/fog/sigma_a".
std::string parameterName(ParameterKind kind, std::string_view owner);

struct ParsedParameterName {
    const ParameterDescription* description;
    std::string_view owner;  // the medium's or material's name; may itself contain '/'
};

// nullopt when the name fits no kind's pattern; whether its owner exists is the scene's concern.
std::optional<ParsedParameterName> parseParameterName(std::string_view name);

// Empty when `value` is finite and within the kind's range, else why not
// ("must be in [-0.99, 0.99], got 1").
std::string valueProblem(const ParameterDescription& description, float value);

}  // namespace vkdr
