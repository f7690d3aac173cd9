// Loading every supported glTF feature into a flattened Scene.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/medium_at.h"
#include "scene/scene_warnings.h"

namespace vkdr::test {
namespace {

const MeshData kTriangle = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {}};

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

glm::vec3 cornerOf(const Scene& scene, size_t triangle, int corner) {
    return scene.positions[scene.triangles[triangle][corner]];
}

glm::vec3 normalOf(const Scene& scene, size_t triangle) {
    glm::vec3 p0 = cornerOf(scene, triangle, 0);
    return glm::normalize(glm::cross(cornerOf(scene, triangle, 1) - p0, cornerOf(scene, triangle, 2) - p0));
}

TEST(LoadScene, FlattensTheNodeHierarchyWithMatricesAndTrs) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int mesh = builder.addMesh("triangle", kTriangle);
    // child: matrix translating by (0, 0, 5); parent: TRS (translate x 1, rotate 90
    // degrees about z, scale 2).
    int child = builder.addNode({{"mesh", mesh},
                                 {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}},
                                false);
    builder.addNode({{"name", "parent"}, {"children", {child}}, {"mesh", mesh},
                     {"translation", {1, 0, 0}},
                     {"rotation", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}},
                     {"scale", {2, 2, 2}}});
    Scene scene = loadScene(builder.writeGltf(directory / "hierarchy.gltf")).scene;

    ASSERT_EQ(scene.triangles.size(), 2u);
    // Parent first: (1,0,0) -> scale (2,0,0) -> rotate (0,2,0) -> translate (1,2,0).
    expectNear(cornerOf(scene, 0, 1), {1, 2, 0});
    // Child: (1,0,0) -> (1,0,5) -> scale (2,0,10) -> rotate (0,2,10) -> (1,2,10).
    expectNear(cornerOf(scene, 1, 1), {1, 2, 10});
    expectNear(cornerOf(scene, 1, 0), {1, 0, 10});
}

TEST(LoadScene, KeepsFrontFacesUnderMirroringTransforms) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int mesh = builder.addMesh("triangle", kTriangle);
    builder.addNode({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
    // The same triangle 1e16 times as large, mirrored by a scale of 1e-16: a determinant
    // of -1e-48, below float's range.
    MeshData vast = kTriangle;
    for (glm::vec3& corner : vast.positions) corner *= 1e16f;
    builder.addNode({{"mesh", builder.addMesh("vast", vast)}, {"scale", {-1e-16, 1e-16, 1e-16}}});
    Scene scene = loadScene(builder.writeGltf(directory / "mirror.gltf")).scene;
    // The triangle faces +z before mirroring; a mirror in x must not turn it around.
    expectNear(normalOf(scene, 0), {0, 0, 1});
    expectNear(normalOf(scene, 1), {0, 0, 1});
}

TEST(LoadScene, ReadsIndexedAndNonIndexedPrimitives) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    MeshData nonIndexed = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {}, {}};
    builder.addNode({{"mesh", builder.addMesh("indexed", floorQuad(1.0f))}});
    builder.addNode({{"mesh", builder.addMesh("soup", nonIndexed)}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "primitives.gltf"));
    const Scene& scene = loaded.scene;

    ASSERT_EQ(scene.triangles.size(), 4u);
    EXPECT_EQ(scene.positions.size(), 10u);
    EXPECT_EQ(scene.uvs.size(), 10u);
    expectNear(cornerOf(scene, 3, 0), {0, 0, 1});
    expectNear(normalOf(scene, 0), {0, 1, 0});
    EXPECT_EQ(scene.uvs[0], glm::vec2(0, 1));
    EXPECT_EQ(scene.uvs[9], glm::vec2(0, 0));  // no TEXCOORD_0: zeros
    // Primitives without a material get the glTF default.
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
    EXPECT_EQ(scene.materials[0].baseColor, glm::vec3(1.0f));
    EXPECT_EQ(scene.triangleMaterial, std::vector<uint32_t>(4, 0));
    EXPECT_TRUE(loaded.warnings.empty());
}

TEST(LoadScene, ReadsTriangleStripsAndFansWithFrontFacesKept) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    MeshData quad = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {0, 1, 2, 3}, {}};
    int strip = builder.addMesh("strip", quad);
    builder.document()["meshes"][size_t(strip)]["primitives"][0]["mode"] = 5;
    MeshData fanQuad = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 3}, {}};
    int fan = builder.addMesh("fan", fanQuad);
    builder.document()["meshes"][size_t(fan)]["primitives"][0]["mode"] = 6;
    builder.addNode({{"mesh", strip}});
    builder.addNode({{"mesh", fan}});
    Scene scene = loadScene(builder.writeGltf(directory / "strips.gltf")).scene;
    ASSERT_EQ(scene.triangles.size(), 4u);
    for (size_t t = 0; t < 4; ++t) {
        expectNear(normalOf(scene, t), {0, 0, 1});
    }
}

TEST(LoadScene, ReadsBinaryGlb) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(2.0f, 1.0f))}});
    Scene scene = loadScene(builder.writeGlb(directory / "quad.glb")).scene;
    ASSERT_EQ(scene.triangles.size(), 2u);
    expectNear(cornerOf(scene, 0, 0), {-2, 1, 2});
}

TEST(LoadScene, DecodesSrgbTexturesWithTheTopRowFirst) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    std::vector<unsigned char> image =
        bmpImage(2, 2, {{255, 0, 0}, {128, 128, 128}, {0, 0, 255}, {0, 255, 0}});
    builder.document()["images"] = {
        {{"name", "checker"}, {"uri", "data:image/bmp;base64," + base64(image)}}};
    builder.document()["textures"] = {{{"source", 0}}};
    int material = builder.addMaterial(
        {{"name", "textured"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 1, 1, 1}}, {"baseColorTexture", {{"index", 0}}}}},
         {"emissiveFactor", {1, 1, 1}},
         {"emissiveTexture", {{"index", 0}}}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    Scene scene = loadScene(builder.writeGltf(directory / "texture.gltf")).scene;

    ASSERT_EQ(scene.textures.size(), 1u);  // one image, shared by both slots
    const Texture& texture = scene.textures[0];
    EXPECT_EQ(texture.name, "checker");
    ASSERT_EQ(texture.width, 2);
    ASSERT_EQ(texture.height, 2);
    EXPECT_EQ(texture.texels[0], glm::vec4(1, 0, 0, 1));  // top left
    float grey = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
    EXPECT_NEAR(texture.texels[1].r, grey, 1e-6f);
    EXPECT_NEAR(grey, 0.2158605f, 1e-6f);
    EXPECT_EQ(texture.texels[2], glm::vec4(0, 0, 1, 1));  // bottom left
    const Material& textured = scene.materials[0];
    EXPECT_EQ(textured.baseColor, glm::vec3(0.5f, 1.0f, 1.0f));
    EXPECT_EQ(textured.baseColorTexture, 0);
    EXPECT_EQ(textured.emissionTexture, 0);
}

TEST(LoadScene, ReadsSamplerWrapModesAndTextureTransforms) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.document()["images"] = {
        {{"uri", "data:image/bmp;base64," + base64(bmpImage(1, 1, {{255, 255, 255}}))}}};
    builder.document()["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}};
    builder.document()["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 0}}};
    // A quarter turn, a scale of (2, 3) and an offset of (0.5, 0.25) take (u, v) = (1, 0)
    // to (0.5, -1.75): scaled to (2, 0), turned counter-clockwise in texture space (whose
    // v runs down) to (0, -2), then moved.
    json transform = {{"offset", {0.5, 0.25}}, {"rotation", std::acos(-1.0) / 2.0}, {"scale", {2, 3}}};
    int material = builder.addMaterial(
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
         {"emissiveFactor", {1, 1, 1}},
         {"emissiveTexture", {{"index", 1}, {"extensions", {{"KHR_texture_transform", transform}}}}}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    builder.document()["extensionsRequired"] = {"KHR_texture_transform"};
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "mapping.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("samplers[0].magFilter: NEAREST (9728) is not supported"), std::string::npos)
        << loaded.warnings[0];

    const Material& m = loaded.scene.materials[0];
    EXPECT_EQ(m.baseColorMapping.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(m.baseColorMapping.wrapT, TextureWrap::MirroredRepeat);
    EXPECT_EQ(m.baseColorMapping.uRow, glm::vec3(1, 0, 0));
    EXPECT_EQ(m.baseColorMapping.vRow, glm::vec3(0, 1, 0));
    EXPECT_EQ(m.emissionMapping.wrapS, TextureWrap::Repeat);  // no sampler: repeat
    EXPECT_EQ(m.emissionMapping.wrapT, TextureWrap::Repeat);
    const glm::vec3 corner(1.0f, 0.0f, 1.0f);
    EXPECT_NEAR(glm::dot(m.emissionMapping.uRow, corner), 0.5f, 1e-6f);
    EXPECT_NEAR(glm::dot(m.emissionMapping.vRow, corner), -1.75f, 1e-6f);
    const glm::vec3 other(0.0f, 1.0f, 1.0f);  // (0, 3) turned to (3, 0), then moved
    EXPECT_NEAR(glm::dot(m.emissionMapping.uRow, other), 3.5f, 1e-6f);
    EXPECT_NEAR(glm::dot(m.emissionMapping.vRow, other), 0.25f, 1e-6f);
}

// floorQuad's uvs mirrored, (1 - u, v).
std::vector<glm::vec2> mirroredQuadUvs() {
    std::vector<glm::vec2> mirrored;
    for (const glm::vec2& uv : floorQuad(1.0f).uvs) {
        mirrored.emplace_back(1.0f - uv.x, uv.y);
    }
    return mirrored;
}

// A textured quad whose material's base colour texture reference is `baseColor` and
// emission texture reference `emission` (null: none); its primitive has TEXCOORD_0 (the
// quad's uvs) and TEXCOORD_1 (them mirrored, 1 - u).
GltfBuilder quadWithTwoUvSets(json baseColor, json emission = nullptr) {
    GltfBuilder builder;
    builder.document()["images"] = {
        {{"uri", "data:image/bmp;base64," + base64(bmpImage(1, 1, {{255, 255, 255}}))}}};
    builder.document()["textures"] = {{{"source", 0}}};
    json material = {{"pbrMetallicRoughness", {{"baseColorTexture", std::move(baseColor)}}}};
    if (!emission.is_null()) {
        material["emissiveFactor"] = {1, 1, 1};
        material["emissiveTexture"] = std::move(emission);
    }
    int mesh = builder.addMesh("quad", floorQuad(1.0f), builder.addMaterial(std::move(material)));
    builder.addVec2Attribute(mesh, "TEXCOORD_1", mirroredQuadUvs());
    builder.addNode({{"mesh", mesh}});
    return builder;
}

// A texture's texCoord (or its KHR_texture_transform's, which replaces it) picks the
// TEXCOORD set its primitives' uvs come from.
TEST(LoadScene, ReadsTheTextureCoordinateSetTheTexturesName) {
    TemporaryDirectory directory;
    LoadedScene second = loadScene(quadWithTwoUvSets({{"index", 0}, {"texCoord", 1}}).writeGltf(directory / "1.gltf"));
    EXPECT_EQ(second.scene.uvs, mirroredQuadUvs());
    EXPECT_TRUE(second.warnings.empty());

    GltfBuilder transformed = quadWithTwoUvSets(
        {{"index", 0}, {"texCoord", 1}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 0}}}}}});
    transformed.document()["extensionsUsed"] = {"KHR_texture_transform"};
    LoadedScene first = loadScene(transformed.writeGltf(directory / "0.gltf"));
    EXPECT_EQ(first.scene.uvs, floorQuad(1.0f).uvs);
    EXPECT_TRUE(first.warnings.empty());

    // Emission alone decides where the base colour has no texture.
    GltfBuilder emissive = quadWithTwoUvSets(nullptr, {{"index", 0}, {"texCoord", 1}});
    emissive.document()["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
    EXPECT_EQ(loadScene(emissive.writeGltf(directory / "e.gltf")).scene.uvs, mirroredQuadUvs());
}

TEST(LoadScene, WarnsOfTextureCoordinateSetsItCannotFollow) {
    TemporaryDirectory directory;
    // One set of uvs a primitive: the base colour texture's wins.
    LoadedScene two = loadScene(quadWithTwoUvSets({{"index", 0}, {"texCoord", 1}}, {{"index", 0}, {"texCoord", 0}})
                                    .writeGltf(directory / "two.gltf"));
    EXPECT_EQ(two.scene.uvs, mirroredQuadUvs());
    ASSERT_EQ(two.warnings.size(), 1u);
    EXPECT_NE(two.warnings[0].find("materials[0].emissiveTexture: looks up TEXCOORD_0 and the base colour texture "
                                   "TEXCOORD_1; a material's textures share one set: both use TEXCOORD_1"),
              std::string::npos)
        << two.warnings[0];
    // An emission texture times an emissiveFactor of 0 shows nothing: its set is not warned of.
    GltfBuilder dark = quadWithTwoUvSets({{"index", 0}, {"texCoord", 1}}, {{"index", 0}, {"texCoord", 0}});
    dark.document()["materials"][0]["emissiveFactor"] = {0, 0, 0};
    LoadedScene unlit = loadScene(dark.writeGltf(directory / "dark.gltf"));
    EXPECT_EQ(unlit.scene.uvs, mirroredQuadUvs());
    EXPECT_TRUE(unlit.warnings.empty()) << unlit.warnings[0];
    // A set the primitive does not have.
    LoadedScene missing =
        loadScene(quadWithTwoUvSets({{"index", 0}, {"texCoord", 2}}).writeGltf(directory / "missing.gltf"));
    EXPECT_EQ(missing.scene.uvs, std::vector<glm::vec2>(4, glm::vec2(0.0f)));
    ASSERT_EQ(missing.warnings.size(), 1u);
    EXPECT_NE(missing.warnings[0].find("meshes[0].primitives[0].attributes: no TEXCOORD_2, which the textures of "
                                       "material 0 look up: its texture coordinates are (0, 0)"),
              std::string::npos)
        << missing.warnings[0];
}

TEST(LoadScene, MultipliesEmissionByEmissiveStrength) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int light = builder.addMaterial(
        {{"name", "lamp"},
         {"emissiveFactor", {1.0, 0.5, 0.25}},
         {"doubleSided", true},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}}});
    builder.addMaterial({{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 0.4, 0.5}}}}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), light)}});
    Scene scene = loadScene(builder.writeGltf(directory / "light.gltf")).scene;

    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[0].emission, glm::vec3(8.0f, 4.0f, 2.0f));
    EXPECT_TRUE(scene.materials[0].doubleSided);
    EXPECT_TRUE(scene.materials[0].isEmissive());
    EXPECT_EQ(scene.materials[1].name, "1");  // unnamed: its index
    expectNear(scene.materials[1].baseColor, {0.2f, 0.3f, 0.4f});
    EXPECT_FALSE(scene.materials[1].isEmissive());
}

// Every material gets a name of its own, so each has parameters of its own: a name used
// twice, and an index that is another material's name, give way to the file's own name.
TEST(LoadScene, NamesEveryMaterialApart) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addMaterial({{"name", "1"}});        // 0: named as material 1's index
    builder.addMaterial(json::object());         // 1: unnamed
    builder.addMaterial({{"name", "1"}});        // 2: a repeat
    builder.addMaterial({{"name", "default"}});  // 3: the default material's name
    for (int material = 0; material < 4; ++material) {
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    }
    builder.addNode({{"mesh", builder.addMesh("plain", floorQuad(1.0f))}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "names.gltf"));
    std::vector<std::string> names;
    for (const Material& material : loaded.scene.materials) {
        names.push_back(material.name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"1", "1_", "2", "default", "default_"}));
    ASSERT_EQ(loaded.warnings.size(), 2u);
    EXPECT_NE(loaded.warnings[0].find("materials[1]: unnamed, and its index is another material's name; this one is "
                                      "named '1_'"),
              std::string::npos)
        << loaded.warnings[0];
    EXPECT_NE(loaded.warnings[1].find("materials[2].name: '1' is used by an earlier material; this one is named '2'"),
              std::string::npos)
        << loaded.warnings[1];
}

// A name may hold control characters (an escape sequence would recolour a terminal):
// warnings quote it escaped, as errors do.
TEST(LoadScene, WarningsQuoteControlCharactersEscaped) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addMaterial({{"name", "red\x1b[31m"}});
    builder.addMaterial({{"name", "red\x1b[31m"}});
    for (int material = 0; material < 2; ++material) {
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    }
    const std::filesystem::path file = builder.writeGltf(directory / "names.gltf");
    LoadedScene loaded = loadScene(file);
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("'red\\x1b[31m' is used by an earlier material"), std::string::npos)
        << loaded.warnings[0];
    loaded.scene.punctualLights.push_back(PunctualLight{.name = "sun\x07"});
    const std::vector<std::string> sceneChecks = sceneWarnings(loaded.scene, file);
    ASSERT_FALSE(sceneChecks.empty());
    EXPECT_NE(sceneChecks[0].find("light 'sun\\x07' is placed by no node"), std::string::npos) << sceneChecks[0];
}

TEST(LoadScene, NamesEveryCameraApart) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    const int camera = builder.addCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}});
    for (int i = 0; i < 3; ++i) {
        builder.addNode({{"name", "cam"}, {"camera", camera}});
    }
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "cameras.gltf"));
    ASSERT_EQ(loaded.scene.cameras.size(), 3u);
    EXPECT_EQ(loaded.scene.cameras[0].name, "cam");
    EXPECT_EQ(loaded.scene.cameras[1].name, "cam_");
    EXPECT_EQ(loaded.scene.cameras[2].name, "cam__");
    ASSERT_EQ(loaded.warnings.size(), 2u);
    EXPECT_NE(loaded.warnings[1].find("camera 'cam' is an earlier camera's name; this one is named 'cam__'"),
              std::string::npos)
        << loaded.warnings[1];
}

TEST(LoadScene, ReadsKhrVolumeAttenuationAsAbsorption) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int glass = builder.addMaterial(
        {{"name", "ink"},
         {"extensions",
          {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
           {"KHR_materials_ior", {{"ior", 1.0}}},
           {"KHR_materials_volume", {{"attenuationColor", {0.5, 0.25, 1.0}}, {"attenuationDistance", 2.0}}}}}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), glass)}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "volume.gltf"));
    const Scene& scene = loaded.scene;

    ASSERT_EQ(scene.media.size(), 1u);
    EXPECT_EQ(scene.media[0].name, "ink");
    expectNear(scene.media[0].sigma_a, {-std::log(0.5f) / 2.0f, -std::log(0.25f) / 2.0f, 0.0f});
    EXPECT_EQ(scene.media[0].sigma_s, glm::vec3(0.0f));
    EXPECT_EQ(scene.media[0].g, 0.0f);
    EXPECT_EQ(scene.materials[0].interiorMedium, 0);
    EXPECT_TRUE(loaded.warnings.empty());
}

TEST(LoadScene, TreatsTransmissionWithoutVolumeAsAClearMediumWithAWarning) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int clear = builder.addMaterial(
        {{"name", "air"},
         {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_ior", {{"ior", 1.0}}}}}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), clear)}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "clear.gltf"));
    ASSERT_EQ(loaded.scene.media.size(), 1u);
    EXPECT_EQ(loaded.scene.media[0].sigma_a, glm::vec3(0.0f));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("without KHR_materials_volume"), std::string::npos);
}

TEST(LoadScene, ReadsParticipatingMediaExtensionWithScalarsBroadcast) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int smoke = builder.addMaterial(
        {{"name", "smoke"},
         {"extensions", {{"VKDR_participating_media", {{"sigma_a", 0.25}, {"sigma_s", {1, 2, 3}}, {"g", -0.5}}}}}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), smoke)}});
    Scene scene = loadScene(builder.writeGltf(directory / "smoke.gltf")).scene;
    ASSERT_EQ(scene.media.size(), 1u);
    EXPECT_EQ(scene.media[0].name, "smoke");
    EXPECT_EQ(scene.media[0].sigma_a, glm::vec3(0.25f));
    EXPECT_EQ(scene.media[0].sigma_s, glm::vec3(1, 2, 3));
    EXPECT_EQ(scene.media[0].g, -0.5f);
    EXPECT_EQ(scene.sceneMedium, kNoMedium);
    EXPECT_EQ(scene.triangleOutsideMedium, std::vector<int32_t>(12, kNoMedium));
}

TEST(LoadScene, ReadsRootMediumWithDefaultNameAndBackground) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["extensions"] = {
        {"VKDR_participating_media", {{"sigma_a", {0.1, 0.2, 0.3}}, {"sigma_s", 0.5}}},
        {"VKDR_background", {{"radiance", {0.5, 0.6, 0.7}}}}};
    Scene scene = loadScene(builder.writeGltf(directory / "fog.gltf")).scene;
    ASSERT_EQ(scene.media.size(), 1u);
    EXPECT_EQ(scene.sceneMedium, 0);
    EXPECT_EQ(scene.media[0].name, "scene");
    expectNear(scene.media[0].sigma_a, {0.1f, 0.2f, 0.3f});
    EXPECT_EQ(scene.media[0].sigma_s, glm::vec3(0.5f));
    expectNear(scene.background, {0.5f, 0.6f, 0.7f});
    EXPECT_EQ(mediumAt(scene, {0, 5, 0}), 0);
}

TEST(LoadScene, ReadsPerspectiveAndOrthographicCamerasInNodeOrder) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    int wide = builder.addCamera({{"name", "wide"}, {"type", "perspective"},
                                  {"perspective", {{"yfov", 1.2}, {"znear", 0.1}, {"aspectRatio", 2.0}}}});
    int plain = builder.addCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}});
    int ortho = builder.addCamera({{"type", "orthographic"},
                                   {"orthographic", {{"xmag", 3}, {"ymag", 1.5}, {"znear", 0}, {"zfar", 10}}}});
    builder.addNode({{"camera", ortho}});
    // Turned to look along +x (a quarter turn about y), scaled: the scale is dropped.
    builder.addNode({{"name", "side"}, {"camera", plain}, {"translation", {0, 1, 2}},
                     {"rotation", {0, -std::sqrt(0.5), 0, std::sqrt(0.5)}}, {"scale", {3, 3, 3}}});
    builder.addNode({{"camera", wide}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "cameras.gltf"));
    const Scene& scene = loaded.scene;

    ASSERT_EQ(scene.cameras.size(), 3u);
    // Unnamed: the camera's place in the file.
    EXPECT_EQ(scene.cameras[0].name, "cameras[2]");
    EXPECT_TRUE(scene.cameras[0].orthographic());
    EXPECT_EQ(scene.cameras[0].orthographicHalfHeight, 1.5f);
    EXPECT_EQ(scene.cameras[0].aspectRatio, 2.0f);
    EXPECT_EQ(scene.cameras[1].name, "side");
    EXPECT_FALSE(scene.cameras[1].orthographic());
    EXPECT_FLOAT_EQ(scene.cameras[1].yfov, 0.5f);
    EXPECT_EQ(scene.cameras[1].aspectRatio, 0.0f);
    glm::vec3 forward = -glm::vec3(scene.cameras[1].cameraToWorld[2]);
    expectNear(forward, {1, 0, 0});
    expectNear(glm::vec3(scene.cameras[1].cameraToWorld[1]), {0, 1, 0});
    expectNear(glm::vec3(scene.cameras[1].cameraToWorld[3]), {0, 1, 2});
    EXPECT_EQ(scene.cameras[2].name, "wide");
    EXPECT_FLOAT_EQ(scene.cameras[2].aspectRatio, 2.0f);
    EXPECT_TRUE(loaded.warnings.empty());
}

// The frame of a camera under `transform` (a node's members), with a triangle to render.
glm::mat4 cameraToWorldUnder(const TemporaryDirectory& directory, json transform) {
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("triangle", kTriangle)}});
    transform["camera"] = builder.addCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
    builder.addNode(transform);
    return loadScene(builder.writeGltf(directory / "camera.gltf")).scene.cameras.at(0).cameraToWorld;
}

void expectSameFrame(const glm::mat4& actual, const glm::mat4& expected) {
    for (int column = 0; column < 4; ++column) {
        SCOPED_TRACE("column " + std::to_string(column));
        expectNear(glm::vec3(actual[column]), glm::vec3(expected[column]));
    }
}

// A mirroring scale or a shear would otherwise mirror or skew the image: the frame is
// always rigid and right-handed, from the node's -Z and +Y.
TEST(LoadScene, CameraFramesAreRigidAndRightHandedUnderMirrorsAndShears) {
    TemporaryDirectory directory;
    const glm::mat4 plain = cameraToWorldUnder(directory, {{"translation", {0, 1, 5}}});
    expectSameFrame(plain, glm::translate(glm::mat4(1.0f), {0, 1, 5}));
    expectSameFrame(cameraToWorldUnder(directory, {{"translation", {0, 1, 5}}, {"scale", {-1, 1, 1}}}), plain);
    expectSameFrame(cameraToWorldUnder(directory, {{"translation", {0, 1, 5}}, {"scale", {2, -3, 0.5}}}),
                    glm::translate(glm::mat4(1.0f), {0, 1, 5}) * glm::scale(glm::mat4(1.0f), {-1, -1, 1}));
    // The node's x axis sheared towards y: its -Z and +Y are the unscaled camera's.
    expectSameFrame(cameraToWorldUnder(directory, {{"matrix", {1, 0.9, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 5, 1}}}),
                    plain);
    // A mirror along z reverses -Z: the camera looks along +z, still upright.
    const glm::mat4 reversed = cameraToWorldUnder(directory, {{"translation", {0, 1, 5}}, {"scale", {1, 1, -1}}});
    expectSameFrame(reversed, glm::translate(glm::mat4(1.0f), {0, 1, 5}) * glm::scale(glm::mat4(1.0f), {-1, 1, -1}));
    // The node's y axis sheared towards x: up leans the same way, at right angles to -Z.
    const glm::mat4 leaning =
        cameraToWorldUnder(directory, {{"matrix", {1, 0, 0, 0, 0.9, 1, 0, 0, 0, 0, 1, 0, 0, 1, 5, 1}}});
    expectNear(glm::vec3(leaning[1]), glm::normalize(glm::vec3(0.9f, 1.0f, 0.0f)));
    expectNear(glm::vec3(leaning[2]), {0, 0, 1});
    EXPECT_NEAR(glm::determinant(glm::mat3(leaning)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::vec3(leaning[0]), glm::vec3(leaning[1])), 0.0f, 1e-6f);
}

// COLOR_0 as RGBA normalized bytes (alpha dropped); a primitive without it is white.
TEST(LoadScene, ReadsVertexColoursAndWhiteWhereAPrimitiveHasNone) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("plain", floorQuad(1.0f))}});
    const int coloured = builder.addMesh("coloured", floorQuad(1.0f, 2.0f));
    const MeshData quad = floorQuad(1.0f);
    ASSERT_EQ(quad.positions.size(), 4u);
    const int view = builder.addBufferView({255, 0, 0, 9, 0, 255, 0, 9, 0, 0, 255, 9, 51, 102, 153, 255});
    builder.document()["accessors"].push_back(
        {{"bufferView", view}, {"componentType", 5121}, {"normalized", true}, {"count", 4}, {"type", "VEC4"}});
    builder.document()["meshes"][size_t(coloured)]["primitives"][0]["attributes"]["COLOR_0"] =
        builder.document()["accessors"].size() - 1;
    builder.addNode({{"mesh", coloured}});
    const Scene scene = loadScene(builder.writeGltf(directory / "colours.gltf")).scene;
    ASSERT_EQ(scene.colors.size(), 8u);
    for (size_t v = 0; v < 4; ++v) EXPECT_EQ(scene.colors[v], glm::vec3(1.0f)) << v;
    EXPECT_EQ(scene.colors[4], glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.colors[5], glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.colors[6], glm::vec3(0, 0, 1));
    expectNear(scene.colors[7], {0.2f, 0.4f, 0.6f});
    // Without any COLOR_0 the scene holds no colours.
    GltfBuilder plain;
    plain.addNode({{"mesh", plain.addMesh("plain", floorQuad(1.0f))}});
    EXPECT_TRUE(loadScene(plain.writeGltf(directory / "plain.gltf")).scene.colors.empty());
}

TEST(LoadScene, VertexNormalsTransformByTheInverseTransposeAndAreUnit) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int withNormals = builder.addMesh("quad", floorQuad(1.0f));
    builder.document()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 0;  // the positions, as normals
    int flat = builder.addMesh("flat", floorQuad(1.0f));
    builder.addNode({{"mesh", withNormals}, {"scale", {2.0, 1.0, 1.0}}});
    builder.addNode({{"mesh", flat}});
    // The same stretch at scales whose inverse leaves float's range (1e-39), or whose
    // determinant does (1e-45), turns the normals alike.
    builder.addNode({{"mesh", withNormals}, {"scale", {2e13, 1e13, 1e13}}});
    builder.addNode({{"mesh", withNormals}, {"scale", {2e-15, 1e-15, 1e-15}}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "normals.gltf"));
    const Scene& scene = loaded.scene;
    EXPECT_TRUE(loaded.warnings.empty());
    ASSERT_EQ(scene.normals.size(), scene.positions.size());
    const size_t perMesh = scene.positions.size() / 4;
    for (size_t v = 0; v < perMesh; ++v) {
        // Position (2x, y, z) came from (x, y, z); its normal is (x / 2, y, z), normalised.
        glm::vec3 source = scene.positions[v] / glm::vec3(2.0f, 1.0f, 1.0f);
        expectNear(scene.normals[v], glm::normalize(source / glm::vec3(2.0f, 1.0f, 1.0f)));
        EXPECT_EQ(scene.normals[perMesh + v], glm::vec3(0.0f));  // no NORMAL: the triangle's own
        expectNear(scene.normals[2 * perMesh + v], scene.normals[v]);
        expectNear(scene.normals[3 * perMesh + v], scene.normals[v]);
    }
}

}  // namespace
}  // namespace vkdr::test
