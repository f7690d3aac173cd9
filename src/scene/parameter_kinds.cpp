#include "scene/parameter_kinds.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

#include "image/finite_pixels.h"

namespace vkdr {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Short of |g| = 1: a phase function this peaked is already a delta for any image we
// can render, and the g gradient's 1/(1-g^2) term blows up beyond it.
constexpr double kMaxAbsAnisotropy = 0.99;

// Why kMaxRadiance is enough: a pixel is the mean of its samples, and a sample gathers,
// at each of its at most kMaxScatteringVertices vertices, the emitter its ray hits (MIS
// weight <= 1) and one light sample, whose scatter * w / pdf_light is at most
// scatter / (2 pdf_scatter) by the power heuristic: half the emission. Albedos and
// emission textures are at most 1, and Russian roulette scales the throughput to at
// most 1 (a grey medium's weight sigma_s T / p is at most 1 too; a chromatic medium's
// spectral MIS weight can reach 3, which this does not cover). So a pixel is at most
// 1.5 kMaxScatteringVertices + 1 times the brightest radiance, emitter's or
// background's, and must stay within what the loss can square (image/finite_pixels.h);
// the film's sum over at most 2^20 samples per pixel is far from float's limit.
static_assert(kMaxRadiance * (1.5 * kMaxScatteringVertices + 1.0) <= double(kMaxPixelMagnitude));

// Relative, so that a fog of sigma = 1e-3 (a scene hundreds of units across) gets a
// step of its own scale; at 0 the one-sided difference steps to 0.015. A changed sigma
// re-routes some free flights (one now ends before a surface instead of after), which
// makes small steps drown in noise; the central difference's error, O((h d)^2) over
// optical paths of length d, stays below 1 % while sigma d < 1.
double sigmaStep(float value) {
    return value > 0.0f ? 0.15 * double(value) : 0.015;
}

double anisotropyStep(float) {
    return 1e-2;
}

// Russian roulette follows the throughput, so an albedo step flips a few roulette
// decisions even with common random numbers: a larger step keeps that noise down.
double albedoStep(float value) {
    return 5e-2 * std::max(std::abs(double(value)), 0.1);
}

double emissionStep(float value) {
    return 1e-2 * std::max(std::abs(double(value)), 0.1);
}

// A voxel's density scales sigma where it is, the way sigma scales a whole medium.
double densityStep(float value) {
    return sigmaStep(value);
}

constexpr std::array<ParameterDescription, 11> kDescriptions = {{
    {ParameterKind::SigmaA, "media/", "/sigma_a", ParameterOwner::Medium, 3, {0.0, kInfinity}, sigmaStep,
     gpu::GradientAccumulator::mediumGradients, gpu::kMediumGradientSigmaA},
    {ParameterKind::SigmaS, "media/", "/sigma_s", ParameterOwner::Medium, 3, {0.0, kInfinity}, sigmaStep,
     gpu::GradientAccumulator::mediumGradients, gpu::kMediumGradientSigmaS},
    {ParameterKind::G, "media/", "/g", ParameterOwner::Medium, 1, {-kMaxAbsAnisotropy, kMaxAbsAnisotropy},
     anisotropyStep, gpu::GradientAccumulator::mediumGradients, gpu::kMediumGradientG},
    {ParameterKind::BaseColor, "materials/", "/base_color", ParameterOwner::Material, 3, {0.0, 1.0}, albedoStep,
     gpu::GradientAccumulator::baseColorGradients, 0},
    {ParameterKind::BaseColorTexture, "materials/", "/base_color_texture", ParameterOwner::Material, 3, {0.0, 1.0},
     albedoStep, gpu::GradientAccumulator::texelGradients, 0},
    {ParameterKind::Emission, "lights/", "/emission", ParameterOwner::Material, 3, {0.0, kMaxRadiance}, emissionStep,
     gpu::GradientAccumulator::emissionGradients, 0},
    // Held to an emitter's range too; a point light's irradiance grows without bound
    // near it (as 1 / distance^2), which the renderer's check of every pixel catches.
    {ParameterKind::LightIntensity, "lights/", "/intensity", ParameterOwner::PunctualLight, 3, {0.0, kMaxRadiance},
     emissionStep, gpu::GradientAccumulator::lightGradients, 0},
    {ParameterKind::Density, "media/", "/density", ParameterOwner::Medium, 1, {0.0, kInfinity}, densityStep,
     gpu::GradientAccumulator::densityGradients, 0},
    // A medium's emission is per unit length: what a segment gathers grows with its
    // length where nothing absorbs (emission / sigma_t where it does), which kMaxRadiance
    // does not bound; the renderer's check of every pixel catches what overflows.
    {ParameterKind::MediumEmission, "media/", "/emission", ParameterOwner::Medium, 3, {0.0, kMaxRadiance},
     emissionStep, gpu::GradientAccumulator::mediumGradients, gpu::kMediumGradientEmission},
    // An emission grid's voxels are strengths that multiply the emission, as densities
    // multiply sigma: the same range and steps.
    {ParameterKind::EmissionGrid, "media/", "/emission_grid", ParameterOwner::Medium, 1, {0.0, kInfinity},
     densityStep, gpu::GradientAccumulator::densityGradients, 0},
    {ParameterKind::AlbedoGrid, "media/", "/albedo_grid", ParameterOwner::Medium, 3, {0.0, 1.0}, albedoStep,
     gpu::GradientAccumulator::densityGradients, 0},
}};

// describe() indexes the table by kind.
static_assert([] {
    for (size_t i = 0; i < kDescriptions.size(); ++i) {
        if (size_t(kDescriptions[i].kind) != i) return false;
    }
    return true;
}());
// Every kind has its bit among the adjoint pipelines' kinds of gradient.
static_assert(gpu::kEveryGradientKind == (1u << kDescriptions.size()) - 1u);

// The shortest text that reads back as the same value: a float prints as the user typed it.
template <typename Number>
std::string numberText(Number value) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, ec == std::errc() ? end : text);
}

}  // namespace

bool ValueRange::contains(float value) const {
    return float(lower) <= value && value <= float(upper);
}

std::span<const ParameterDescription> parameterDescriptions() {
    return kDescriptions;
}

const ParameterDescription& describe(ParameterKind kind) {
    return kDescriptions[size_t(kind)];
}

std::string parameterPattern(const ParameterDescription& description) {
    const char* owner = description.owner == ParameterOwner::Medium     ? "<medium>"
                        : description.owner == ParameterOwner::Material ? "<material>"
                                                                        : "<light>";
    return std::string(description.prefix) + owner + std::string(description.field);
}

std::string parameterName(ParameterKind kind, std::string_view owner) {
    const ParameterDescription& description = describe(kind);
    return std::string(description.prefix) + std::string(owner) + std::string(description.field);
}

std::optional<ParsedParameterName> parseParameterName(std::string_view name) {
    for (const ParameterDescription& description : kDescriptions) {
        if (name.size() >= description.prefix.size() + description.field.size() &&
            name.starts_with(description.prefix) && name.ends_with(description.field)) {
            std::string_view owner = name.substr(description.prefix.size(),
                                                 name.size() - description.prefix.size() - description.field.size());
            return ParsedParameterName{&description, owner};
        }
    }
    return std::nullopt;
}

std::string valueProblem(const ParameterDescription& description, float value) {
    if (!std::isfinite(value)) {
        return "must be finite, got " + numberText(value);
    }
    if (description.range.contains(value)) {
        return "";
    }
    const ValueRange& range = description.range;
    return (std::isinf(range.upper) ? "must be >= " + numberText(range.lower)
                                    : "must be in [" + numberText(range.lower) + ", " + numberText(range.upper) + "]") +
           ", got " + numberText(value);
}

}  // namespace vkdr
