// Writing fitted parameters back into glTF: every parameter survives a load-change-
// write-load round trip, in both medium spellings, with external and GLB buffers.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "core/error.h"
#include "expect_error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"
#include "scene/write_scene.h"

namespace vkdr::test {
namespace {

// Float values pass through decimal JSON, and KHR_materials_volume through exp/log of
// a float colour: equal to a few float ulps.
void expectSameParameters(const Scene& expected, const Scene& actual) {
    ASSERT_EQ(parameterNames(expected), parameterNames(actual));
    for (const std::string& name : parameterNames(expected)) {
        std::vector<float> want = getParameter(expected, name);
        std::vector<float> got = getParameter(actual, name);
        ASSERT_EQ(want.size(), got.size()) << name;
        for (size_t i = 0; i < want.size(); ++i) {
            EXPECT_NEAR(got[i], want[i], 2e-6f * std::max(1.0f, std::abs(want[i]))) << name << "[" << i << "]";
        }
    }
}

json readJson(const std::filesystem::path& file) { return json::parse(std::ifstream(file)); }

std::string readText(const std::filesystem::path& file) {
    std::ifstream stream(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
}

Scene writeAndReload(const std::filesystem::path& original, const Scene& scene, const std::filesystem::path& out) {
    writeSceneWithParameters(original, scene, out);
    return loadScene(out).scene;
}

void set(Scene& scene, const std::string& name, std::vector<float> values) { setParameter(scene, name, values); }

int addKhrVolumeBox(GltfBuilder& builder) {
    int ink = builder.addMaterial(
        {{"name", "ink"},
         {"extensions",
          {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
           {"KHR_materials_ior", {{"ior", 1.0}}},
           {"KHR_materials_volume", {{"attenuationColor", {0.5, 0.25, 1.0}}, {"attenuationDistance", 2.0}}}}}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), ink)}});
    return ink;
}

TEST(WriteScene, RoundTripsEveryParameterOfTheExampleScene) {
    TemporaryDirectory directory;
    std::filesystem::path original = std::filesystem::path(VKDR_TEST_DATA_DIR) / "example.gltf";
    Scene scene = loadScene(original).scene;
    set(scene, "media/haze/sigma_a", {0.011f, 0.012f, 0.013f});
    set(scene, "media/haze/sigma_s", {0.5f});
    set(scene, "media/haze/g", {-0.25f});
    set(scene, "media/haze/emission", {0.25f, 0.5f, 1.0f});
    set(scene, "media/smoke/sigma_a", {0.2f, 0.0f, 0.7f});
    set(scene, "media/smoke/sigma_s", {2.5f, 1.0f, 0.125f});
    set(scene, "media/smoke/g", {0.9f});
    set(scene, "media/smoke/emission", {4.0f, 0.0f, 1.5f});
    set(scene, "materials/floor/base_color", {0.1f, 0.55f, 1.0f});
    set(scene, "lights/lamp/emission", {3.0f, 12.5f, 0.0f});

    Scene reloaded = writeAndReload(original, scene, directory / "fitted.gltf");
    expectSameParameters(scene, reloaded);
    EXPECT_EQ(reloaded.triangles.size(), scene.triangles.size());
}

TEST(WriteScene, WritesPunctualLightIntensitiesAsAColourAtMostOneTimesAnIntensity) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f))}});
    builder.document()["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"name", "bulb"}, {"type", "point"}, {"color", {1.0, 0.5, 0.5}}, {"intensity", 2.0}},
        {{"name", "sun"}, {"type", "directional"}}};
    builder.addNode({{"translation", {0.0, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    std::filesystem::path original = builder.writeGltf(directory / "lights.gltf");
    Scene scene = loadScene(original).scene;
    set(scene, "lights/bulb/intensity", {0.25f, 7.5f, 3.0f});
    set(scene, "lights/sun/intensity", {0.0f});

    std::filesystem::path out = directory / "fitted.gltf";
    Scene reloaded = writeAndReload(original, scene, out);
    expectSameParameters(scene, reloaded);
    json bulb = readJson(out)["extensions"]["KHR_lights_punctual"]["lights"][0];
    EXPECT_EQ(bulb["intensity"].get<double>(), 7.5);
    EXPECT_EQ(bulb["color"][1].get<double>(), 1.0);
}

TEST(WriteScene, SplitsEmissionIntoAFactorAtMostOneAndAStrength) {
    TemporaryDirectory directory;
    std::filesystem::path original = std::filesystem::path(VKDR_TEST_DATA_DIR) / "example.gltf";
    Scene scene = loadScene(original).scene;
    set(scene, "lights/lamp/emission", {40.0f, 20.0f, 10.0f});
    writeSceneWithParameters(original, scene, directory / "bright.gltf");
    json lamp = readJson(directory / "bright.gltf")["materials"][1];
    EXPECT_EQ(lamp["emissiveFactor"], json({1.0, 0.5, 0.25}));
    EXPECT_EQ(lamp["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 40.0);

    set(scene, "lights/lamp/emission", {0.5f});
    writeSceneWithParameters(original, scene, directory / "dim.gltf");
    lamp = readJson(directory / "dim.gltf")["materials"][1];
    EXPECT_EQ(lamp["emissiveFactor"], json({0.5, 0.5, 0.5}));
    EXPECT_FALSE(lamp.contains("extensions"));

    // Fitted to 0, the lamp is still an emitter of the written scene, so a further fit
    // finds its parameter.
    set(scene, "lights/lamp/emission", {0.0f});
    writeSceneWithParameters(original, scene, directory / "off.gltf");
    lamp = readJson(directory / "off.gltf")["materials"][1];
    EXPECT_EQ(lamp["emissiveFactor"], json({1.0, 1.0, 1.0}));
    EXPECT_EQ(lamp["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 0);
    Scene off = loadScene(directory / "off.gltf").scene;
    EXPECT_EQ(getParameter(off, "lights/lamp/emission"), std::vector<float>(3, 0.0f));
}

// A box of the Khronos-spelled medium "ink" with `values` set, written and reloaded
// (the same parameters come back); returns the written document.
json fittedKhrVolumeBox(const TemporaryDirectory& directory,
                        const std::vector<std::pair<std::string, std::vector<float>>>& values) {
    GltfBuilder builder;
    addKhrVolumeBox(builder);
    std::filesystem::path original = builder.writeGltf(directory / "ink.gltf");
    Scene scene = loadScene(original).scene;
    for (const auto& [name, value] : values) {
        set(scene, name, value);
    }
    Scene reloaded = writeAndReload(original, scene, directory / "fitted.gltf");
    expectSameParameters(scene, reloaded);
    return readJson(directory / "fitted.gltf");
}

TEST(WriteScene, KeepsTheKhronosSpellingForAnAbsorbingMedium) {
    TemporaryDirectory directory;
    json extensions =
        fittedKhrVolumeBox(directory, {{"media/ink/sigma_a", {0.3f, 0.0f, 4.0f}}})["materials"][0]["extensions"];
    EXPECT_FALSE(extensions.contains("VKDR_participating_media"));
    ASSERT_TRUE(extensions.contains("KHR_materials_volume"));
    // Without it (glTF's default 0) other tools would read a thin wall and no absorption.
    EXPECT_EQ(extensions["KHR_materials_volume"].value("thicknessFactor", 0.0), 1.0);
}

TEST(WriteScene, SwitchesAKhronosMediumThatScattersToOurSpelling) {
    TemporaryDirectory directory;
    json written = fittedKhrVolumeBox(directory, {{"media/ink/sigma_s", {0.75f}}, {"media/ink/g", {0.5f}}});
    EXPECT_TRUE(written["materials"][0]["extensions"].contains("VKDR_participating_media"));
    EXPECT_NE(std::find(written["extensionsUsed"].begin(), written["extensionsUsed"].end(), "VKDR_participating_media"),
              written["extensionsUsed"].end());
}

TEST(WriteScene, SwitchesAKhronosMediumThatEmitsToOurSpelling) {
    TemporaryDirectory directory;
    json written = fittedKhrVolumeBox(directory, {{"media/ink/emission", {0.5f, 2.0f, 0.0f}}});
    EXPECT_TRUE(written["materials"][0]["extensions"].contains("VKDR_participating_media"));
}

TEST(WriteScene, RoundTripsAnAbsorptionOfZero) {
    TemporaryDirectory directory;
    fittedKhrVolumeBox(directory, {{"media/ink/sigma_a", {0.0f}}});
}

TEST(WriteScene, GivesPrimitivesWithoutAMaterialTheFittedDefaultMaterial) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    std::filesystem::path original = builder.writeGltf(directory / "bare.gltf");
    Scene scene = loadScene(original).scene;
    set(scene, "materials/default/base_color", {0.25f, 0.5f, 0.75f});
    expectSameParameters(scene, writeAndReload(original, scene, directory / "fitted.gltf"));
}

TEST(WriteScene, WritesTheBinaryChunkOfAGlbBesideTheGltf) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    addKhrVolumeBox(builder);
    std::filesystem::path original = builder.writeGlb(directory / "ink.glb");
    Scene scene = loadScene(original).scene;
    set(scene, "media/ink/sigma_a", {0.125f});
    std::filesystem::create_directories(directory / "out");

    Scene reloaded = writeAndReload(original, scene, directory / "out" / "scene.gltf");
    expectSameParameters(scene, reloaded);
    EXPECT_TRUE(std::filesystem::is_regular_file(directory / "out" / "scene.bin"));
    EXPECT_EQ(readJson(directory / "out" / "scene.gltf")["buffers"][0]["uri"], "scene.bin");
}

// The written scene loads by the default rule: files outside its directory are copied beside it.
TEST(WriteScene, CopiesExternalBuffersOutsideTheOutputDirectoryBesideIt) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    addKhrVolumeBox(builder);
    std::filesystem::create_directories(directory / "source" / "data");
    std::filesystem::path glb = builder.writeGlb(directory / "ink.glb");
    // An external-buffer .gltf made from the GLB's own chunk, in source/ with data/ below.
    Scene scene = loadScene(glb).scene;
    writeSceneWithParameters(glb, scene, directory / "source" / "data" / "ink.gltf");
    json document = readJson(directory / "source" / "data" / "ink.gltf");
    std::filesystem::rename(directory / "source" / "data" / "ink.gltf", directory / "source" / "ink.gltf");
    document["buffers"][0]["uri"] = "data/ink.bin";
    writeText(directory / "source" / "ink.gltf", document.dump());
    std::filesystem::create_directories(directory / "fits" / "run1");

    Scene reloaded = writeAndReload(directory / "source" / "ink.gltf", scene, directory / "fits" / "run1" / "scene.gltf");
    expectSameParameters(scene, reloaded);
    EXPECT_EQ(readJson(directory / "fits" / "run1" / "scene.gltf")["buffers"][0]["uri"], "scene.buffers0.bin");
}

TEST(WriteScene, RefersToExternalBuffersInsideTheOutputDirectoryWhereTheyAre) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    addKhrVolumeBox(builder);
    std::filesystem::create_directories(directory / "data");
    std::filesystem::path glb = builder.writeGlb(directory / "ink.glb");
    Scene scene = loadScene(glb).scene;
    writeSceneWithParameters(glb, scene, directory / "data" / "ink.gltf");

    Scene reloaded = writeAndReload(directory / "data" / "ink.gltf", scene, directory / "fitted.gltf");
    expectSameParameters(scene, reloaded);
    EXPECT_EQ(readJson(directory / "fitted.gltf")["buffers"][0]["uri"], "data/ink.bin");
}

// The written scene is the original with the values: an original (or a buffer it reads)
// changed since the load, by a re-export say, would mix new contents with old values.
TEST(WriteScene, RefusesAnOriginalThatChangedSinceTheLoad) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    addKhrVolumeBox(builder);
    std::filesystem::path glb = builder.writeGlb(directory / "ink.glb");
    writeSceneWithParameters(glb, loadScene(glb).scene, directory / "ink.gltf");  // with data ink.bin beside it
    const std::filesystem::path original = directory / "ink.gltf", buffer = directory / "ink.bin";
    const std::string text = readText(original), bytes = readText(buffer);

    Scene scene = loadScene(original).scene;
    writeText(original, text + " ");
    expectErrorMentioning([&] { writeSceneWithParameters(original, scene, directory / "out.gltf"); },
                          {"ink.gltf", "has changed since the scene was loaded"});
    writeText(original, text);
    writeText(buffer, std::string(bytes).replace(0, 1, 1, char(bytes[0] ^ 1)));
    expectErrorMentioning([&] { writeSceneWithParameters(original, scene, directory / "out.gltf"); },
                          {"ink.bin", "has changed since the scene was loaded"});
    EXPECT_FALSE(std::filesystem::exists(directory / "out.gltf"));
    writeText(buffer, bytes);
    writeSceneWithParameters(original, scene, directory / "out.gltf");
    EXPECT_TRUE(std::filesystem::exists(directory / "out.gltf"));
}

// A quad whose material "painted" has a base colour texture of `image` (a glTF image).
GltfBuilder paintedQuad(json image) {
    GltfBuilder builder;
    builder.document()["images"] = {std::move(image)};
    builder.document()["textures"] = {{{"source", 0}}};
    int material = builder.addMaterial(
        {{"name", "painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    return builder;
}

// A 2x1 BMP, red then blue, as the file `file`.
void writeCheckerBmp(const std::filesystem::path& file) {
    const std::vector<unsigned char> bmp = bmpImage(2, 1, {{255, 0, 0}, {0, 0, 255}});
    writeText(file, std::string(bmp.begin(), bmp.end()));
}

TEST(WriteScene, WritesFittedTexelsAsAnSrgbPng) {
    TemporaryDirectory directory;
    std::filesystem::path original =
        paintedQuad({{"name", "checker"},
                     {"uri", "data:image/bmp;base64," + base64(bmpImage(2, 1, {{255, 0, 0}, {0, 0, 255}}))}})
            .writeGltf(directory / "painted.gltf");
    Scene scene = loadScene(original).scene;
    set(scene, "materials/painted/base_color_texture", {0.25f, 0.5f, 0.75f, 0.05f, 0.9f, 0.0f});

    Scene reloaded = writeAndReload(original, scene, directory / "fitted.gltf");
    EXPECT_EQ(readJson(directory / "fitted.gltf")["images"][0]["uri"], "fitted.image0.png");
    std::vector<float> want = getParameter(scene, "materials/painted/base_color_texture");
    std::vector<float> got = getParameter(reloaded, "materials/painted/base_color_texture");
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < want.size(); ++i) {
        // Half an 8-bit sRGB step, in linear terms, is at most 0.0045 (at 1).
        EXPECT_NEAR(got[i], want[i], 0.0045f) << i;
    }
}

// A texture whose texels are written anew is not also copied beside a scene written
// outside the original's directory: the written scene refers to the new image alone.
TEST(WriteScene, FittedTextureFileIsNotCopiedToo) {
    TemporaryDirectory directory;
    std::filesystem::create_directories(directory / "in");
    std::filesystem::create_directories(directory / "out");
    writeCheckerBmp(directory / "in" / "checker.bmp");
    std::filesystem::path original = paintedQuad({{"uri", "checker.bmp"}}).writeGltf(directory / "in" / "painted.gltf");
    Scene scene = loadScene(original).scene;

    writeAndReload(original, scene, directory / "out" / "fitted.gltf");
    std::vector<std::string> written;
    for (const auto& entry : std::filesystem::directory_iterator(directory / "out")) {
        written.push_back(entry.path().filename().string());
    }
    std::sort(written.begin(), written.end());
    EXPECT_EQ(written, (std::vector<std::string>{"fitted.gltf", "fitted.image0.png"}));
}

// Every file is checked before any is written: a refusal found at the texture leaves
// no binary chunk written beside the output (which could have replaced that of a scene
// written there before).
TEST(WriteScene, ARefusalWritesNothing) {
    TemporaryDirectory directory;
    // The texture's file is named as the written scene's texture would be.
    writeCheckerBmp(directory / "out.image0.png");
    std::filesystem::path original = paintedQuad({{"uri", "out.image0.png"}}).writeGlb(directory / "painted.glb");
    Scene scene = loadScene(original).scene;

    expectErrorMentioning([&] { writeSceneWithParameters(original, scene, directory / "out.gltf"); },
                          {"out.image0.png", "which the scene reads"});
    EXPECT_FALSE(std::filesystem::exists(directory / "out.bin"));
    EXPECT_FALSE(std::filesystem::exists(directory / "out.gltf"));
}

TEST(WriteScene, NamesAnUnreadableOriginal) {
    TemporaryDirectory directory;
    Scene scene;
    try {
        writeSceneWithParameters(directory / "missing.gltf", scene, directory / "out.gltf");
        FAIL() << "no error";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("missing.gltf"), std::string::npos) << error.what();
    }
    EXPECT_FALSE(std::filesystem::exists(directory / "out.gltf"));
}

// An original that is not among the scene's sources (here, a scene made in memory) is
// read for the first time when the scene is written: by the loader's rules.
TEST(WriteScene, ReadsAnOriginalByTheLoadersRules) {
    TemporaryDirectory directory;
    const std::filesystem::path original = directory / "original.gltf";
    const std::string tooDeep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(600, '[') +
                                std::string(600, ']') + "}";
    const std::vector<std::pair<std::string, std::vector<std::string>>> refusals = {
        {"{\"asset\": {\"version\": \"2.0\"}, \"asset\": {\"version\": \"2.0\"}}", {"asset", "given twice"}},
        {tooDeep, {"levels deep", "at most 512"}},
        {"[1, 2]", {"not an object"}},
        {"{\"asset\": ", {"not an object"}},
    };
    for (const auto& [text, parts] : refusals) {
        writeText(original, text);
        std::vector<std::string> expected = {"original.gltf"};
        expected.insert(expected.end(), parts.begin(), parts.end());
        expectErrorMentioning([&] { writeSceneWithParameters(original, Scene{}, directory / "out.gltf"); }, expected);
        EXPECT_FALSE(std::filesystem::exists(directory / "out.gltf")) << text.substr(0, 40);
    }
}

}  // namespace
}  // namespace vkdr::test
