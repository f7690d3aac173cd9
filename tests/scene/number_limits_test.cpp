// Numbers a scene may hold, and what is said about them: emission and background
// radiance are bounded so that no pixel can overflow, numbers beyond float range are
// called that (not "not a number"), and a scene that will render black or has emitters
// that cannot emit is warned about.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "expect_error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "scene/scene_warnings.h"

namespace vkdr::test {
namespace {

json emissive(const std::string& name, double strength) {
    return {{"name", name},
            {"emissiveFactor", {1.0, 0.5, 0.25}},
            {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}};
}

// A grey floor and a quad of material `light` above it.
GltfBuilder litFloor(json light) {
    GltfBuilder builder;
    int floor = builder.addMaterial({{"name", "floor"}});
    int emitter = builder.addMaterial(std::move(light));
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f), floor)}});
    builder.addNode({{"mesh", builder.addMesh("light", floorQuad(0.2f, 1.0f), emitter)}});
    return builder;
}

void expectLoadErrorMentioning(const std::filesystem::path& file, const std::vector<std::string>& parts) {
    expectErrorMentioning([&] { loadScene(file); }, parts);
}

bool mentions(const std::vector<std::string>& lines, const std::string& part) {
    for (const std::string& line : lines) {
        if (line.find(part) != std::string::npos) return true;
    }
    return false;
}

TEST(NumberLimits, EmissionIsBoundedEverywhereItIsSet) {
    EXPECT_EQ(describe(ParameterKind::Emission).range.upper, kMaxRadiance);
    TemporaryDirectory directory;
    // emissiveFactor x emissiveStrength: the product is what is bounded.
    const double atLimit = kMaxRadiance;
    Scene scene = loadScene(litFloor(emissive("light", atLimit)).writeGltf(directory / "limit.gltf")).scene;
    EXPECT_EQ(getParameter(scene, "lights/light/emission").front(), float(kMaxRadiance));
    expectLoadErrorMentioning(litFloor(emissive("light", 1e38)).writeGltf(directory / "bright.gltf"),
                              {"materials[1].extensions.KHR_materials_emissive_strength.emissiveStrength",
                               "must be in [0, 1e+12]", "got 1e+38"});
    expectLoadErrorMentioning(litFloor(emissive("light", 2.5e12)).writeGltf(directory / "just_above.gltf"),
                              {"emissiveFactor[0] x emissiveStrength", "must be in [0, 1e+12]"});
    // --set and the optimiser's range share the bound.
    expectErrorMentioning([&] { applyAssignment(scene, "lights/light/emission=1e38"); },
                          {"lights/light/emission", "must be in [0, 1e+12], got 1e+38"});
    expectErrorMentioning([&] { setParameter(scene, "lights/light/emission", std::vector<float>{2e12f}); },
                          {"must be in [0, 1e+12]"});
}

TEST(NumberLimits, BackgroundRadianceIsBoundedLikeEmission) {
    TemporaryDirectory directory;
    GltfBuilder builder = litFloor(emissive("light", 1.0));
    builder.document()["extensions"]["VKDR_background"] = {{"radiance", {1.0, 1e20, 1.0}}};
    expectLoadErrorMentioning(builder.writeGltf(directory / "background.gltf"),
                              {"extensions.VKDR_background.radiance", "must be in [0, 1e+12], got 1e+20"});
}

TEST(NumberLimits, NumbersBeyondFloatRangeAreCalledThat) {
    Scene scene;
    scene.media.push_back(Medium{"fog"});
    for (const char* text : {"1e-50", "1e50", "-1e50", "1e39"}) {
        expectErrorMentioning([&] { applyAssignment(scene, std::string("media/fog/sigma_a=") + text); },
                              {std::string("'") + text + "' is out of float range"});
    }
    try {
        applyAssignment(scene, "media/fog/g=1e50");
    } catch (const Error& error) {
        EXPECT_EQ(std::string(error.what()).find("not a number"), std::string::npos) << error.what();
    }
    // Still not numbers: these are.
    expectErrorMentioning([&] { applyAssignment(scene, "media/fog/g=0.1x"); }, {"'0.1x' is not a number"});
    // A subnormal float is in range.
    applyAssignment(scene, "media/fog/sigma_a=1e-40");
    EXPECT_GT(getParameter(scene, "media/fog/sigma_a").front(), 0.0f);
}

TEST(NumberLimits, LoaderSaysWhenANumberIsBeyondFloatRange) {
    TemporaryDirectory directory;
    std::string text = litFloor(emissive("light", 12345.0)).gltfText();
    size_t strength = text.find("12345.0");
    ASSERT_NE(strength, std::string::npos) << text;
    text.replace(strength, 7, "1e39");
    expectLoadErrorMentioning(writeText(directory / "float.gltf", text),
                              {"emissiveStrength", "got 1e+39", "beyond float range"});
}

// Coordinates that fit in a float but whose products do not: the renderer's edge cross
// product overflows and no ray would hit the triangle, which would vanish without a word.
TEST(NumberLimits, TrianglesTooLargeForAFloatNormalAreRefused) {
    TemporaryDirectory directory;
    GltfBuilder builder = litFloor(emissive("light", 5.0));
    builder.addNode({{"name", "far"}, {"mesh", builder.addMesh("big", floorQuad(1e19f))}});
    expectLoadErrorMentioning(builder.writeGltf(directory / "big.gltf"),
                              {"meshes[2].primitives[0]", "triangle 0 at nodes[2] ('far') is too large in world space",
                               "cross product"});
    // The same through a node's scale.
    GltfBuilder scaled = litFloor(emissive("light", 5.0));
    scaled.addNode({{"mesh", scaled.addMesh("big", floorQuad(1.0f))}, {"scale", {1e19, 1, 1e19}}});
    expectLoadErrorMentioning(scaled.writeGltf(directory / "scaled.gltf"),
                              {"meshes[2].primitives[0]", "triangle 0 at nodes[2] is too large in world space"});
    // 1e18 is still fine.
    GltfBuilder large = litFloor(emissive("light", 5.0));
    large.addNode({{"mesh", large.addMesh("large", floorQuad(1e18f))}});
    EXPECT_NO_THROW(loadScene(large.writeGltf(directory / "large.gltf")));
}

// Applied as floats, they would make every vertex below the node infinite, and the
// mesh's POSITION would take the blame.
TEST(NumberLimits, NodeTransformsBeyondFloatRangeAreNamed) {
    TemporaryDirectory directory;
    const std::vector<std::pair<std::string, json>> transforms = {
        {"translation", {0, 1e39, 0}},
        {"scale", {1, 1e39, 1}},
        {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1e39, 0, 1}}};
    for (const auto& [key, value] : transforms) {
        SCOPED_TRACE(key);
        GltfBuilder builder = litFloor(emissive("light", 5.0));
        builder.addNode({{"mesh", 0}, {key, value}});
        expectLoadErrorMentioning(builder.writeGltf(directory / "node.gltf"),
                                  {"nodes[2]." + key + (key == "matrix" ? "[13]" : "[1]"),
                                   "must be finite, got 1e+39: beyond float range"});
    }
}

TEST(SceneWarnings, NoneForALitScene) {
    TemporaryDirectory directory;
    Scene scene = loadScene(litFloor(emissive("light", 5.0)).writeGltf(directory / "lit.gltf")).scene;
    EXPECT_TRUE(sceneWarnings(scene, "scene.gltf").empty());
}

TEST(SceneWarnings, ASceneWithoutLightWillBeBlack) {
    TemporaryDirectory directory;
    Scene scene = loadScene(litFloor(emissive("light", 5.0)).writeGltf(directory / "lit.gltf")).scene;
    applyAssignment(scene, "lights/light/emission=0");
    std::vector<std::string> warnings = sceneWarnings(scene, "scene.gltf");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(mentions(warnings, "no light")) << warnings[0];
    EXPECT_TRUE(mentions(warnings, "black")) << warnings[0];
    // A background lights the scene.
    scene.background = glm::vec3(0.0f, 0.0f, 0.1f);
    EXPECT_TRUE(sceneWarnings(scene, "scene.gltf").empty());
}

// A homogeneous scene medium fills all space, so light from infinitely far (the
// background, a directional light) reaches nothing through it, but in a channel where
// it has no extinction; a grid medium's density is 0 outside its grid.
TEST(SceneWarnings, ASceneWhoseOnlyLightsTheSceneMediumExtinguishesWillBeBlack) {
    TemporaryDirectory directory;
    Scene scene = loadScene(litFloor(emissive("light", 5.0)).writeGltf(directory / "lit.gltf")).scene;
    applyAssignment(scene, "lights/light/emission=0");
    // A sun that no node places lights nothing, and no scene medium is to blame.
    scene.punctualLights.push_back(PunctualLight{.name = "unplaced", .type = PunctualLight::Type::Directional});
    std::vector<std::string> warnings = sceneWarnings(scene, "lit.gltf");
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_TRUE(mentions(warnings, "no punctual light has an intensity above 0")) << warnings[1];
    EXPECT_FALSE(mentions(warnings, "directional light that")) << warnings[1];
    scene.punctualLights.pop_back();
    scene.background = glm::vec3(0.2f, 0.3f, 0.4f);
    EXPECT_TRUE(sceneWarnings(scene, "lit.gltf").empty());
    Medium fog;
    fog.name = "fog";
    fog.sigma_a = glm::vec3(0.1f, 0.0f, 0.0f);
    fog.sigma_s = glm::vec3(0.0f, 0.2f, 0.3f);
    scene.media.push_back(fog);
    scene.sceneMedium = int32_t(scene.media.size() - 1);
    warnings = sceneWarnings(scene, "lit.gltf");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(mentions(warnings, "lit.gltf: the scene has no light")) << warnings[0];
    EXPECT_TRUE(mentions(warnings, "the background is extinguished by the scene medium 'fog'")) << warnings[0];
    // A sun is extinguished as the background is.
    scene.punctualLights.push_back(PunctualLight{.name = "sun", .type = PunctualLight::Type::Directional});
    scene.lightPlacements.push_back(LightPlacement{.light = uint32_t(scene.punctualLights.size() - 1)});
    warnings = sceneWarnings(scene, "lit.gltf");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(mentions(warnings, "is a directional light that the scene medium 'fog' extinguishes")) << warnings[0];
    // Where a channel of the light meets no extinction, it passes.
    scene.media.back().sigma_s.z = 0.0f;
    EXPECT_TRUE(sceneWarnings(scene, "lit.gltf").empty());
    scene.punctualLights.back().intensity = glm::vec3(1.0f, 1.0f, 0.0f);
    scene.background = glm::vec3(0.2f, 0.3f, 0.0f);
    EXPECT_EQ(sceneWarnings(scene, "lit.gltf").size(), 1u);
    // A grid medium is empty outside its grid.
    SceneDensityGrid puff;
    puff.grid.size = glm::ivec3(1);
    puff.grid.values = {1.0f};
    scene.densityGrids.push_back(puff);
    scene.media.back().densityGrid = 0;
    EXPECT_TRUE(sceneWarnings(scene, "lit.gltf").empty());
}

TEST(SceneWarnings, EmittersOfZeroAreaAreCountedPerMaterial) {
    TemporaryDirectory directory;
    GltfBuilder builder = litFloor(emissive("light", 5.0));
    int sliver = builder.addMaterial(emissive("sliver", 5.0));
    // Two triangles whose vertices are collinear, and one with a repeated vertex.
    MeshData degenerate{{{0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0, 2, 0}, {0, 2, 0}, {1, 2, 0}}, {0, 1, 2, 2, 1, 0, 3, 4, 5}, {}};
    builder.addNode({{"mesh", builder.addMesh("sliver", degenerate, sliver)}});
    Scene scene = loadScene(builder.writeGltf(directory / "sliver.gltf")).scene;
    std::vector<std::string> warnings = sceneWarnings(scene, "scene.gltf");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(mentions(warnings, "3 emissive triangles of material 'sliver'")) << warnings[0];
    EXPECT_TRUE(mentions(warnings, "zero area")) << warnings[0];

    // With only degenerate emitters, the scene is dark as well.
    applyAssignment(scene, "lights/light/emission=0");
    warnings = sceneWarnings(scene, "scene.gltf");
    EXPECT_EQ(warnings.size(), 2u);
    EXPECT_TRUE(mentions(warnings, "no light"));
}

}  // namespace
}  // namespace vkdr::test
