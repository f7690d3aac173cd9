// Named scene parameters: listing, reading, validated writing, assignments.
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "expect_error.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

Scene sceneWithEverything() {
    Scene scene;
    scene.media.push_back({"fog", glm::vec3(0.1f), glm::vec3(0.2f), 0.3f});
    scene.media.push_back({"smoke", glm::vec3(0.5f), glm::vec3(1.5f), 0.6f});
    Material white;
    white.name = "white";
    white.baseColor = glm::vec3(0.7f);
    Material light;
    light.name = "light";
    light.emission = glm::vec3(17.0f, 12.0f, 4.0f);
    light.emitter = true;
    Material boundary;
    boundary.name = "smoke";
    boundary.interiorMedium = 1;
    scene.materials = {white, light, boundary};
    return scene;
}

TEST(Parameters, ListsMediaThenBaseColoursThenLights) {
    std::vector<std::string> expected = {
        "media/fog/sigma_a",   "media/fog/sigma_s",   "media/fog/g",   "media/fog/emission",
        "media/smoke/sigma_a", "media/smoke/sigma_s", "media/smoke/g", "media/smoke/emission",
        "materials/white/base_color", "materials/light/base_color",
        "lights/light/emission"};
    EXPECT_EQ(parameterNames(sceneWithEverything()), expected);
}

TEST(Parameters, GetsCurrentValues) {
    Scene scene = sceneWithEverything();
    EXPECT_EQ(getParameter(scene, "media/smoke/sigma_s"), std::vector<float>(3, 1.5f));
    EXPECT_EQ(getParameter(scene, "media/fog/g"), std::vector<float>{0.3f});
    EXPECT_EQ(getParameter(scene, "lights/light/emission"), (std::vector<float>{17.0f, 12.0f, 4.0f}));
    EXPECT_EQ(getParameter(scene, "materials/white/base_color"), std::vector<float>(3, 0.7f));
}

TEST(Parameters, SetsRgbValuesAndBroadcastsOneValue) {
    Scene scene = sceneWithEverything();
    std::vector<float> rgb = {0.1f, 0.2f, 0.3f};
    setParameter(scene, "media/fog/sigma_a", rgb);
    EXPECT_EQ(scene.media[0].sigma_a, glm::vec3(0.1f, 0.2f, 0.3f));
    std::vector<float> one = {0.05f};
    setParameter(scene, "media/smoke/sigma_s", one);
    EXPECT_EQ(scene.media[1].sigma_s, glm::vec3(0.05f));
    setParameter(scene, "materials/white/base_color", one);
    EXPECT_EQ(scene.materials[0].baseColor, glm::vec3(0.05f));
    std::vector<float> g = {-0.9f};
    setParameter(scene, "media/smoke/g", g);
    EXPECT_EQ(scene.media[1].g, -0.9f);
}

TEST(Parameters, AnAssignmentSplitsAtItsLastEqualsSign) {
    Scene scene = sceneWithEverything();
    scene.media[0].name = "a=b";
    applyAssignment(scene, "media/a=b/sigma_a=0.25");
    EXPECT_EQ(scene.media[0].sigma_a, glm::vec3(0.25f));
    applyAssignment(scene, "media/a=b/g=-0.5");
    EXPECT_EQ(scene.media[0].g, -0.5f);
}

// sceneWithEverything with a texture on "white" and a density, emission and albedo grid in "smoke": an owner
// for every kind of parameter.
Scene sceneWithEveryKind() {
    Scene scene = sceneWithEverything();
    scene.textures.push_back({"checker", 2, 1, {glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), glm::vec4(0.4f, 0.5f, 0.6f, 1.0f)}});
    scene.materials[0].baseColorTexture = 0;
    PunctualLight bulb;
    bulb.name = "bulb";
    scene.punctualLights.push_back(bulb);
    SceneDensityGrid grid;
    grid.grid.size = glm::ivec3(3, 1, 1);
    grid.grid.values = {0.5f, 1.0f, 0.0f};
    scene.densityGrids.push_back(grid);
    scene.media[1].densityGrid = 0;  // "smoke"
    SceneDensityGrid flame;
    flame.grid.size = glm::ivec3(2, 2, 1);
    flame.grid.values = {0.0f, 2.0f, 1.0f, 0.5f};
    scene.densityGrids.push_back(flame);
    scene.media[1].emissionGrid = 1;
    SceneDensityGrid albedo;
    albedo.grid.size = glm::ivec3(1, 2, 1);
    albedo.grid.channels = 3;
    albedo.grid.values = {0.1f, 0.2f, 0.3f, 1.0f, 0.5f, 0.0f};
    scene.densityGrids.push_back(albedo);
    scene.media[1].albedoGrid = 2;
    return scene;
}

std::string ownerOf(ParameterKind kind) {
    switch (kind) {
    case ParameterKind::SigmaA:
    case ParameterKind::SigmaS:
    case ParameterKind::G:
    case ParameterKind::MediumEmission: return "fog";
    case ParameterKind::Emission: return "light";
    case ParameterKind::LightIntensity: return "bulb";
    case ParameterKind::Density:
    case ParameterKind::EmissionGrid:
    case ParameterKind::AlbedoGrid: return "smoke";
    default: return "white";
    }
}

TEST(ParameterKinds, SettingAcceptsEveryKindsRangeEndsAndRefusesBeyond) {
    for (const ParameterDescription& description : parameterDescriptions()) {
        Scene scene = sceneWithEveryKind();
        const std::string name = parameterName(description.kind, ownerOf(description.kind));
        const float lower = float(description.range.lower), upper = float(description.range.upper);
        setParameter(scene, name, std::vector<float>{lower});
        EXPECT_EQ(getParameter(scene, name).front(), lower) << name;
        expectErrorMentioning([&] { setParameter(scene, name, std::vector<float>{std::nextafter(lower, -1e30f)}); },
                              {name, "must be"});
        if (std::isfinite(upper)) {
            setParameter(scene, name, std::vector<float>{upper});
            EXPECT_EQ(getParameter(scene, name).front(), upper) << name;
            expectErrorMentioning([&] { setParameter(scene, name, std::vector<float>{std::nextafter(upper, 1e30f)}); },
                                  {name, "must be in ["});
        } else {
            setParameter(scene, name, std::vector<float>{std::numeric_limits<float>::max()});
        }
    }
}

TEST(ParameterKinds, GIsKeptWithinPlusMinus0Point99) {
    const ValueRange& range = describe(ParameterKind::G).range;
    EXPECT_EQ(range.lower, -0.99);
    EXPECT_EQ(range.upper, 0.99);
    Scene scene = sceneWithEverything();
    setParameter(scene, "media/fog/g", std::vector<float>{-0.99f});
    setParameter(scene, "media/fog/g", std::vector<float>{0.99f});
    EXPECT_EQ(scene.media[0].g, 0.99f);
    expectErrorMentioning([&] { setParameter(scene, "media/fog/g", std::vector<float>{0.995f}); },
                          {"media/fog/g", "must be in [-0.99, 0.99], got 0.995"});
    expectErrorMentioning([&] { setParameter(scene, "media/fog/g", std::vector<float>{-0.991f}); },
                          {"must be in [-0.99, 0.99], got -0.991"});
}

TEST(ParameterKinds, NamesParseBackToTheirKindAndOwner) {
    for (const ParameterDescription& description : parameterDescriptions()) {
        const std::string name = parameterName(description.kind, "Props/Red");
        std::optional<ParsedParameterName> parsed = parseParameterName(name);
        ASSERT_TRUE(parsed) << name;
        EXPECT_EQ(parsed->description->kind, description.kind) << name;
        EXPECT_EQ(parsed->owner, "Props/Red") << name;
    }
    EXPECT_EQ(parameterPattern(describe(ParameterKind::BaseColorTexture)), "materials/<material>/base_color_texture");
    EXPECT_EQ(parameterPattern(describe(ParameterKind::G)), "media/<medium>/g");
    for (const char* unknown : {"media/sigma_a", "media/fog/sigma_t", "lights/white/base_color", "nonsense", ""}) {
        EXPECT_FALSE(parseParameterName(unknown)) << unknown;
    }
}

TEST(ParameterKinds, ChannelsAreThoseSettingAndGettingUse) {
    Scene scene = sceneWithEveryKind();
    for (const ParameterDescription& description : parameterDescriptions()) {
        const std::string name = parameterName(description.kind, ownerOf(description.kind));
        const size_t groups = description.kind == ParameterKind::BaseColorTexture ? scene.textures[0].texels.size()
                              : description.kind == ParameterKind::Density   ? scene.densityGrids[0].grid.voxelCount()
                              : description.kind == ParameterKind::EmissionGrid ? scene.densityGrids[1].grid.voxelCount()
                              : description.kind == ParameterKind::AlbedoGrid   ? scene.densityGrids[2].grid.voxelCount()
                                                                                : 1;
        EXPECT_EQ(getParameter(scene, name).size(), description.channels * groups) << name;
    }
}

// The steps grad --check takes: relative for sigma (0.015 at 0), fixed for g, 5 % of an
// albedo and 1 % of an emission (at least 0.1 of either).
TEST(ParameterKinds, FiniteDifferenceStepsPerKind) {
    auto step = [](ParameterKind kind, float value) { return describe(kind).finiteDifferenceStep(value); };
    for (ParameterKind sigma : {ParameterKind::SigmaA, ParameterKind::SigmaS}) {
        EXPECT_DOUBLE_EQ(step(sigma, 2.0f), 0.3);
        EXPECT_DOUBLE_EQ(step(sigma, 0.0f), 0.015);
    }
    EXPECT_DOUBLE_EQ(step(ParameterKind::G, 0.0f), 0.01);
    EXPECT_DOUBLE_EQ(step(ParameterKind::G, -0.9f), 0.01);
    for (ParameterKind albedo : {ParameterKind::BaseColor, ParameterKind::BaseColorTexture}) {
        EXPECT_DOUBLE_EQ(step(albedo, 0.5f), 0.025);
        EXPECT_DOUBLE_EQ(step(albedo, 0.0f), 0.005);
    }
    EXPECT_DOUBLE_EQ(step(ParameterKind::Emission, 8.0f), 0.08);
    EXPECT_DOUBLE_EQ(step(ParameterKind::Emission, 0.0f), 0.001);
}

TEST(Parameters, BaseColorTextureIsTheRgbOfEveryTexel) {
    Scene scene = sceneWithEverything();
    scene.textures.push_back({"checker", 2, 1, {glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), glm::vec4(0.4f, 0.5f, 0.6f, 1.0f)}});
    scene.materials[0].baseColorTexture = 0;
    EXPECT_EQ(parameterNames(scene)[9], "materials/white/base_color_texture");
    EXPECT_EQ(getParameter(scene, "materials/white/base_color_texture"),
              (std::vector<float>{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}));
    std::vector<float> texels = {0.6f, 0.5f, 0.4f, 0.3f, 0.2f, 0.1f};
    setParameter(scene, "materials/white/base_color_texture", texels);
    EXPECT_EQ(scene.textures[0].texels[1], glm::vec4(0.3f, 0.2f, 0.1f, 1.0f));  // alpha untouched
    std::vector<float> wrongCount = {0.1f, 0.2f, 0.3f};
    expectErrorMentioning([&] { setParameter(scene, "materials/white/base_color_texture", wrongCount); },
                          {"materials/white/base_color_texture", "expected 1 or 6 values, got 3"});
    expectErrorMentioning([&] { getParameter(scene, "materials/light/base_color_texture"); },
                          {"unknown parameter 'materials/light/base_color_texture'"});
}

// Two materials that share a texture give two names of its texels; every other pair of
// names holds values of its own.
TEST(Parameters, NamesOfTheSameValuesShareTheirStorage) {
    Scene scene = sceneWithEveryKind();
    std::map<const float*, std::string> nameOf;
    for (const std::string& name : parameterNames(scene)) {
        const auto [first, isNew] = nameOf.emplace(parameterStorageAddress(scene, name), name);
        EXPECT_TRUE(isNew) << name << " and " << first->second;
    }
    scene.materials[1].baseColorTexture = 0;
    EXPECT_EQ(parameterStorageAddress(scene, "materials/white/base_color_texture"),
              parameterStorageAddress(scene, "materials/light/base_color_texture"));
    expectErrorMentioning([&] { parameterStorageAddress(scene, "media/haze/g"); },
                          {"unknown parameter 'media/haze/g'"});
}

TEST(Parameters, LightEmissionCanReturnFromZero) {
    Scene scene = sceneWithEverything();
    std::vector<float> zero = {0.0f};
    setParameter(scene, "lights/light/emission", zero);
    std::vector<float> bright = {5.0f};
    setParameter(scene, "lights/light/emission", bright);
    EXPECT_EQ(scene.materials[1].emission, glm::vec3(5.0f));
}

TEST(Parameters, RejectsOutOfRangeAndNonFiniteValues) {
    Scene scene = sceneWithEverything();
    auto set = [&](const char* name, std::vector<float> values) {
        return [&scene, name, values] { setParameter(scene, name, values); };
    };
    float nan = std::numeric_limits<float>::quiet_NaN();
    float inf = std::numeric_limits<float>::infinity();
    expectErrorMentioning(set("media/fog/sigma_a", {-0.1f}), {"media/fog/sigma_a", "must be >= 0, got -0.1"});
    expectErrorMentioning(set("media/fog/sigma_s", {0.1f, nan, 0.1f}), {"media/fog/sigma_s", "must be finite, got nan"});
    expectErrorMentioning(set("media/fog/sigma_s", {inf}), {"must be finite, got inf"});
    // Of many values, the message says which.
    expectErrorMentioning(set("media/fog/sigma_a", {0.1f, -2.0f, 0.3f}),
                          {"parameter media/fog/sigma_a: value 1 of 3 (counted from 0): must be", "got -2"});
    expectErrorMentioning(set("media/fog/g", {1.0f}), {"media/fog/g", "must be in [-0.99, 0.99], got 1"});
    expectErrorMentioning(set("media/fog/g", {0.1f, 0.2f, 0.3f}), {"media/fog/g", "expected 1 value, got 3"});
    expectErrorMentioning(set("media/fog/sigma_a", {0.1f, 0.2f}), {"expected 1 or 3 values, got 2"});
    expectErrorMentioning(set("materials/white/base_color", {1.5f}), {"materials/white/base_color", "must be in [0, 1]"});
    expectErrorMentioning(set("lights/light/emission", {-1.0f}), {"lights/light/emission", "must be in [0, 1e+12], got -1"});
    EXPECT_EQ(scene.media[0].sigma_a, glm::vec3(0.1f));  // untouched by the failures
}

TEST(Parameters, UnknownNamesListTheValidOnes) {
    Scene scene = sceneWithEverything();
    for (const char* unknown : {"media/haze/sigma_a", "media/fog/sigma_t", "materials/smoke/base_color",
                                "lights/white", "nonsense"}) {
        expectErrorMentioning([&] { getParameter(scene, unknown); },
                              {std::string("unknown parameter '") + unknown + "'", "media/fog/sigma_a",
                               "lights/light/emission"});
    }
}

TEST(Parameters, MaterialNamesMayContainSlashes) {
    Scene scene;
    Material material;
    material.name = "Props/Red";
    scene.materials = {material};
    applyAssignment(scene, "materials/Props/Red/base_color=0.5,0,0");
    EXPECT_EQ(scene.materials[0].baseColor, glm::vec3(0.5f, 0.0f, 0.0f));
}

TEST(Parameters, AppliesAssignments) {
    Scene scene = sceneWithEverything();
    applyAssignment(scene, "media/fog/sigma_s=0.25");
    EXPECT_EQ(scene.media[0].sigma_s, glm::vec3(0.25f));
    applyAssignment(scene, "lights/light/emission=1,2,3e1");
    EXPECT_EQ(scene.materials[1].emission, glm::vec3(1.0f, 2.0f, 30.0f));
    // A leading '+' as the decimal options read it; a second sign after it is no number.
    applyAssignment(scene, "media/fog/sigma_a=+0.5,1,+2");
    EXPECT_EQ(scene.media[0].sigma_a, glm::vec3(0.5f, 1.0f, 2.0f));
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g=+-0.1"); }, {"'+-0.1' is not a number"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g=+"); }, {"'+' is not a number"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g"); },
                          {"assignment 'media/fog/g'", "expected NAME=VALUE"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g=0.1x"); },
                          {"assignment 'media/fog/g=0.1x'", "'0.1x' is not a number"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/sigma_a=1,,2"); }, {"'' is not a number"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g=nan"); }, {"media/fog/g", "must be finite"});
    expectErrorMentioning([&] { applyAssignment(scene, "media/nope/g=0"); }, {"unknown parameter 'media/nope/g'"});
}

}  // namespace
}  // namespace vkdr::test
