// Input that loadScene must reject with a message naming the file and the field.
#include <sys/resource.h>

#include <cmath>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/scene_warnings.h"

namespace vkdr::test {
namespace {

GltfBuilder boxWithMaterial(json material) {
    GltfBuilder builder;
    int index = builder.addMaterial(std::move(material));
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), index)}});
    return builder;
}

json mediumMaterial(json participatingMedia) {
    return {{"name", "smoke"}, {"extensions", {{"VKDR_participating_media", std::move(participatingMedia)}}}};
}

TEST(LoadSceneErrors, MissingFile) {
    TemporaryDirectory directory;
    expectLoadError(directory / "absent.gltf", {"no such file"});
}

TEST(LoadSceneErrors, EmptyFileName) {
    try {
        loadScene("");
        ADD_FAILURE() << "an empty file name loaded";
    } catch (const Error& error) {
        EXPECT_STREQ(error.what(), "the scene's file name is empty");
    }
}

TEST(LoadSceneErrors, MalformedJsonIncludesTheParserMessage) {
    TemporaryDirectory directory;
    expectLoadError(writeText(directory / "broken.gltf", R"({"asset": {"version": "2.0"}, "nodes": [)"),
                    {"cannot parse glTF", "parse error"});
}

// tinygltf's parser recurses per level: nesting 100000 deep would overflow its stack.
// A level is a container around the deepest value: the root's "extras" is at level 1.
TEST(LoadSceneErrors, JsonNestedDeeperThanTheParserReads) {
    TemporaryDirectory directory;
    auto nestedExtras = [&](int levels) {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
        std::string text = builder.gltfText();
        const int inside = levels - 1;  // arrays within "extras"
        text.insert(text.rfind('}'), ", \"extras\": [" + std::string(inside, '[') + std::string(inside, ']') + "]");
        return writeText(directory / ("nested" + std::to_string(levels) + ".gltf"), text);
    };
    expectLoadError(nestedExtras(100000), {"100000 levels deep", "at most 512"});
    expectLoadError(nestedExtras(513), {"513 levels deep", "at most 512"});
    EXPECT_NO_THROW(loadScene(nestedExtras(512)));
    // Read in memory linear in the depth: the path of every level held whole took
    // 15 GB for the 200 KB file nested 100,000 deep.
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    EXPECT_LT(usage.ru_maxrss, 1024L * 1024L) << "peak resident KiB";
}

// glTF requires each key once in an object; a JSON parser would keep one of the two.
TEST(LoadSceneErrors, AKeyGivenTwiceInOneObject) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int paint = builder.addMaterial({{"name", "paint"}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), paint)}});
    std::string text = builder.gltfText();
    const std::string name = "\"name\": \"paint\"";
    ASSERT_NE(text.find(name), std::string::npos);
    std::string twice = text;
    twice.replace(twice.find(name), name.size(), name + ", \"name\": \"ink\"");
    expectLoadError(writeText(directory / "material.gltf", twice), {"materials[0].name", "given twice"});
    std::string rootTwice = text;
    rootTwice.insert(rootTwice.rfind('}'), ", \"scene\": 0, \"scene\": 0");
    expectLoadError(writeText(directory / "root.gltf", rootTwice), {": scene: given twice"});
    EXPECT_NO_THROW(loadScene(writeText(directory / "once.gltf", text)));
}

// Only buffers[0] stands for a GLB's BIN chunk; tinygltf reads a uri that is not text
// as none.
TEST(LoadSceneErrors, AGlbBufferAfterTheFirstWithoutAUri) {
    TemporaryDirectory directory;
    auto expectRefused = [&](const json& later, const std::string& problem) {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
        builder.document()["buffers"] = json::array({later});
        expectLoadError(builder.writeGlb(directory / "two.glb"), {"buffers[1].uri", problem});
    };
    expectRefused({{"byteLength", 4}}, "only buffers[0]");
    expectRefused({{"byteLength", 4}, {"uri", 5}}, "expected a string");
}

TEST(LoadSceneErrors, TextureCoordinatesThatAreNotFinite) {
    TemporaryDirectory directory;
    for (float bad : {std::nanf(""), INFINITY}) {
        MeshData quad = floorQuad(1.0f);
        quad.uvs[2].y = bad;
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", quad)}});
        expectLoadError(builder.writeGltf(directory / "uv.gltf"),
                        {"meshes[0].primitives[0].attributes.TEXCOORD_0", "texture coordinate 2 is not finite"});
    }
}

TEST(LoadSceneErrors, OutOfRangeIndices) {
    TemporaryDirectory directory;
    {
        GltfBuilder builder;
        int mesh = builder.addMesh("quad", floorQuad(1.0f), 3);
        builder.addNode({{"mesh", mesh}});
        expectLoadError(builder.writeGltf(directory / "material.gltf"),
                        {"meshes[0].primitives[0].material", "material 3 out of range"});
    }
    {
        GltfBuilder builder;
        builder.addNode({{"mesh", 4}});
        expectLoadError(builder.writeGltf(directory / "mesh.gltf"), {"nodes[0].mesh", "mesh 4 out of range"});
    }
    {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
        builder.document()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 9;
        expectLoadError(builder.writeGltf(directory / "accessor.gltf"),
                        {"meshes[0].primitives[0].attributes.TEXCOORD_0", "accessor 9 out of range"});
    }
    {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
        builder.document()["accessors"][0]["bufferView"] = 7;
        expectLoadError(builder.writeGltf(directory / "view.gltf"),
                        {"accessors[0].bufferView", "buffer view 7 out of range"});
    }
    {
        GltfBuilder builder;
        MeshData quad = floorQuad(1.0f);
        quad.indices[4] = 17;
        builder.addNode({{"mesh", builder.addMesh("quad", quad)}});
        expectLoadError(builder.writeGltf(directory / "vertex.gltf"),
                        {"meshes[0].primitives[0].indices", "vertex index 17 out of range (4 vertices)"});
    }
    {
        json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}}}};
        expectLoadError(boxWithMaterial(material).writeGltf(directory / "texture.gltf"),
                        {"materials[0].pbrMetallicRoughness.baseColorTexture.index", "texture 2 out of range"});
    }
}

// glTF requires every index in range, in what the scene uses and what it does not: a file
// other readers refuse is refused here too, though the loader would not read the entry.
TEST(LoadSceneErrors, OutOfRangeIndicesAreRefusedWhereTheSceneDoesNotUseThem) {
    TemporaryDirectory directory;
    auto changed = [&](const std::function<void(json&)>& change) {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
        change(builder.document());
        return builder.writeGltf(directory / "unused.gltf");
    };
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 9; }),
                    {"meshes[0].primitives[0].attributes.JOINTS_0", "accessor 9 out of range"});
    expectLoadError(changed([](json& d) {
                        d["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 9}}}}}}});
                    }),
                    {"meshes[1].primitives[0].attributes.POSITION", "accessor 9 out of range"});
    expectLoadError(changed([](json& d) { d["nodes"].push_back({{"mesh", 9}}); }),
                    {"nodes[1].mesh", "mesh 9 out of range (1 meshes)"});
    expectLoadError(changed([](json& d) { d["nodes"][0]["skin"] = 0; }),
                    {"nodes[0].skin", "skin 0 out of range (0 skins)"});
    expectLoadError(changed([](json& d) { d["materials"] = {{{"normalTexture", {{"index", 7}}}}}; }),
                    {"materials[0].normalTexture.index", "texture 7 out of range (0 textures)"});
    expectLoadError(changed([](json& d) { d["images"] = {{{"bufferView", 5}, {"mimeType", "image/png"}}}; }),
                    {"images[0].bufferView", "buffer view 5 out of range"});
    expectLoadError(changed([](json& d) { d["scenes"] = {{{"nodes", {0, 3}}}}; }),
                    {"scenes[0].nodes[1]", "node 3 out of range"});
    expectLoadError(changed([](json& d) { d["scene"] = 2; }), {"scene", "scene 2 out of range"});
}

TEST(LoadSceneErrors, BufferShorterThanItsAccessor) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["accessors"][0]["count"] = 40;
    expectLoadError(builder.writeGltf(directory / "short.gltf"),
                    {"accessors[0]", "40 elements need 480 bytes but bufferViews[0] holds 48"});
}

TEST(LoadSceneErrors, AccessorOfNoElements) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["accessors"][0]["count"] = 0;
    expectLoadError(builder.writeGltf(directory / "empty.gltf"), {"accessors[0].count", "must be a number > 0, got 0"});
}

TEST(LoadSceneErrors, AnEmptyListOfScenes) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["scenes"] = json::array();
    builder.document().erase("scene");
    expectLoadError(builder.writeGltf(directory / "no_scenes.gltf"), {"scenes", "an empty array"});
}

TEST(LoadSceneErrors, NonTrianglePrimitive) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("lines", floorQuad(1.0f))}});
    builder.document()["meshes"][0]["primitives"][0]["mode"] = 1;
    expectLoadError(builder.writeGltf(directory / "lines.gltf"),
                    {"meshes[0].primitives[0].mode", "only triangles are supported, got mode 1 (LINES)"});
}

TEST(LoadSceneErrors, SceneWithoutTriangles) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    expectLoadError(builder.writeGltf(directory / "empty.gltf"), {"no triangles"});
}

TEST(LoadSceneErrors, NegativeSigma) {
    TemporaryDirectory directory;
    expectLoadError(
        boxWithMaterial(mediumMaterial({{"sigma_a", {0.1, -0.2, 0.1}}})).writeGltf(directory / "negative.gltf"),
        {"materials[0].extensions.VKDR_participating_media.sigma_a", "must be >= 0, got -0.2"});
}

TEST(LoadSceneErrors, NegativeMediumEmission) {
    TemporaryDirectory directory;
    expectLoadError(
        boxWithMaterial(mediumMaterial({{"emission", {1.0, -0.5, 0.0}}})).writeGltf(directory / "negative.gltf"),
        {"materials[0].extensions.VKDR_participating_media.emission", "must be in [0, 1e+12], got -0.5"});
}

// A scene-wide homogeneous medium fills all space: where it emits without attenuating,
// a ray that leaves the scene would gather its emission without end, and where it
// attenuates little, more than a radiance may be. An enclosed medium, or a scene-wide
// one that attenuates enough in that channel, loads.
TEST(LoadSceneErrors, SceneWideEmissionWithoutAttenuation) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["extensions"]["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.1, 0.0, 0.1}}, {"emission", {1.0, 1.0, 0.0}}};
    expectLoadError(builder.writeGltf(directory / "fog.gltf"),
                    {"extensions.VKDR_participating_media.emission[1]", "sigma_a + sigma_s = 0", "infinitely bright"});
    builder.document()["extensions"]["VKDR_participating_media"]["sigma_s"] = {0.0, 0.2, 0.0};
    EXPECT_EQ(loadScene(builder.writeGltf(directory / "fog.gltf")).scene.media.at(0).emission, glm::vec3(1.0f, 1.0f, 0.0f));
    // Attenuating too little: emission / sigma_t beyond the radiance bound.
    builder.document()["extensions"]["VKDR_participating_media"]["sigma_s"] = {0.0, 1e-30, 0.0};
    builder.document()["extensions"]["VKDR_participating_media"]["emission"] = {1.0, 1e12, 0.0};
    expectLoadError(builder.writeGltf(directory / "fog.gltf"),
                    {"extensions.VKDR_participating_media.emission[1]", "media/fog/emission / (sigma_a + sigma_s)",
                     "= 9.99999993e+41 in channel 1", "beyond the 1e+12"});
    Scene enclosed = loadScene(boxWithMaterial(mediumMaterial({{"emission", 2.0}})).writeGltf(directory / "box.gltf")).scene;
    EXPECT_EQ(enclosed.media.at(0).emission, glm::vec3(2.0f));
}

TEST(LoadSceneErrors, AnisotropyOfOneOrMore) {
    TemporaryDirectory directory;
    expectLoadError(boxWithMaterial(mediumMaterial({{"g", 1.2}})).writeGltf(directory / "g.gltf"),
                    {"materials[0].extensions.VKDR_participating_media.g", "must be in [-0.99, 0.99], got 1.2"});
}

// The loader holds g to the range --set and the optimiser use: its ends load, beyond does not.
TEST(LoadSceneErrors, AnisotropyBeyondTheParameterRange) {
    TemporaryDirectory directory;
    for (double g : {-0.99, 0.99}) {
        Scene scene = loadScene(boxWithMaterial(mediumMaterial({{"g", g}})).writeGltf(directory / "end.gltf")).scene;
        EXPECT_EQ(scene.media.at(0).g, float(g));
    }
    expectLoadError(boxWithMaterial(mediumMaterial({{"g", 0.995}})).writeGltf(directory / "g.gltf"),
                    {"materials[0].extensions.VKDR_participating_media.g", "must be in [-0.99, 0.99], got 0.995"});
}

TEST(LoadSceneErrors, NumbersBeyondFloatRange) {
    TemporaryDirectory directory;
    GltfBuilder builder = boxWithMaterial(mediumMaterial({{"sigma_s", 12345.0}}));
    std::string text = builder.gltfText();
    size_t number = text.find("12345.0");
    // Finite as a double, infinite as the float it is stored in.
    expectLoadError(writeText(directory / "float.gltf", std::string(text).replace(number, 7, "1e39")),
                    {"materials[0].extensions.VKDR_participating_media.sigma_s", "must be finite, got 1e+39"});
    // Beyond double range the JSON parser itself refuses.
    expectLoadError(writeText(directory / "double.gltf", std::string(text).replace(number, 7, "1e999")),
                    {"cannot parse glTF", "number overflow", "1e999"});
}

TEST(LoadSceneErrors, RootMediumWithInvalidAnisotropy) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["extensions"]["VKDR_participating_media"] = {{"name", "fog"}, {"g", -1.0}};
    expectLoadError(builder.writeGltf(directory / "fog.gltf"),
                    {"extensions.VKDR_participating_media.g", "must be in [-0.99, 0.99], got -1"});
}

TEST(LoadSceneErrors, RefractionIsNotSupported) {
    TemporaryDirectory directory;
    json glass = {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                  {"KHR_materials_ior", {{"ior", 1.5}}}}}};
    expectLoadError(boxWithMaterial(glass).writeGltf(directory / "glass.gltf"),
                    {"materials[0].extensions.KHR_materials_ior.ior", "refraction is not supported", "got 1.5"});
    json defaultIor = {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}};
    expectLoadError(boxWithMaterial(defaultIor).writeGltf(directory / "default_ior.gltf"),
                    {"KHR_materials_ior.ior", "the default when absent"});
}

TEST(LoadSceneErrors, ZeroAttenuationColorMeansInfiniteAbsorption) {
    TemporaryDirectory directory;
    json ink = {{"extensions",
                 {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                  {"KHR_materials_ior", {{"ior", 1.0}}},
                  {"KHR_materials_volume", {{"attenuationColor", {0.5, 0.0, 0.5}}, {"attenuationDistance", 1.0}}}}}};
    expectLoadError(boxWithMaterial(ink).writeGltf(directory / "ink.gltf"),
                    {"materials[0].extensions.KHR_materials_volume.attenuationColor[1]", "infinite absorption"});
}

TEST(LoadSceneErrors, AttenuationDistanceTooSmallForAFloatAbsorption) {
    TemporaryDirectory directory;
    json ink = {{"extensions",
                 {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                  {"KHR_materials_ior", {{"ior", 1.0}}},
                  {"KHR_materials_volume", {{"attenuationColor", {0.5, 0.5, 0.5}}, {"attenuationDistance", 1e-45}}}}}};
    expectLoadError(boxWithMaterial(ink).writeGltf(directory / "ink.gltf"),
                    {"materials[0].extensions.KHR_materials_volume.attenuationDistance", "too small",
                     "must be finite"});
}

TEST(LoadSceneErrors, OpenMediumBoundary) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int smoke = builder.addMaterial(mediumMaterial({{"sigma_s", 1.0}}));
    MeshData open = box({0, 0, 0}, {1, 1, 1});
    open.indices.resize(open.indices.size() - 6);  // no top face
    builder.addNode({{"name", "puff"}, {"mesh", builder.addMesh("smokebox", open, smoke)}});
    expectLoadError(builder.writeGltf(directory / "open.gltf"),
                    {"meshes[0] ('smokebox') at nodes[0] ('puff')", "medium 'smoke'", "not a closed mesh"});
}

TEST(LoadSceneErrors, DuplicateMediumNames) {
    TemporaryDirectory directory;
    GltfBuilder builder = boxWithMaterial(mediumMaterial({{"sigma_s", 1.0}}));
    builder.document()["extensions"]["VKDR_participating_media"] = {{"name", "smoke"}};
    expectLoadError(builder.writeGltf(directory / "names.gltf"),
                    {"extensions.VKDR_participating_media.name", "medium names must be unique"});
}

TEST(LoadSceneErrors, UnsupportedRequiredExtension) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f))}});
    builder.document()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expectLoadError(builder.writeGltf(directory / "draco.gltf"),
                    {"extensionsRequired[0]", "KHR_draco_mesh_compression is not supported"});
    builder.document()["extensionsRequired"] = {"KHR_materials_volume", "EXT_meshopt_compression"};
    expectLoadError(builder.writeGltf(directory / "meshopt.gltf"),
                    {"extensionsRequired[1]", "EXT_meshopt_compression is not supported"});
}

// A quad whose base colour texture has `sampler` and the texture transform `transform`.
GltfBuilder quadWithTextureMapping(json sampler, json transform) {
    GltfBuilder builder;
    builder.document()["images"] = {
        {{"uri", "data:image/bmp;base64," + base64(bmpImage(1, 1, {{255, 255, 255}}))}}};
    builder.document()["samplers"] = {std::move(sampler)};
    builder.document()["textures"] = {{{"source", 0}, {"sampler", 0}}};
    int material = builder.addMaterial(
        {{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", std::move(transform)}}}}}}}});
    builder.addNode({{"mesh", builder.addMesh("quad", floorQuad(1.0f), material)}});
    return builder;
}

TEST(LoadSceneErrors, UnknownWrapModesAndMalformedTextureTransforms) {
    TemporaryDirectory directory;
    const std::string field = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform";
    expectLoadError(quadWithTextureMapping({{"wrapS", 33071}, {"wrapT", 1234}}, json::object())
                        .writeGltf(directory / "wrap.gltf"),
                    {"samplers[0].wrapT", "must be 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"offset", {1.0}}}).writeGltf(directory / "offset.gltf"),
                    {field + ".offset", "expected an array of 2 numbers"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"scale", {1.0, "2"}}}).writeGltf(directory / "scale.gltf"),
                    {field + ".scale", "expected an array of 2 numbers"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"rotation", 1e39}}).writeGltf(directory / "rotation.gltf"),
                    {field + ".rotation", "beyond float range"});
    // What tinygltf would drop for the default, silently: a wrap mode not written as an
    // integer, a transform that is not an object, empty members.
    expectLoadError(quadWithTextureMapping({{"wrapS", 33071.0}}, json::object()).writeGltf(directory / "float.gltf"),
                    {"samplers[0].wrapS", "expected an integer", "got 33071.0"});
    expectLoadError(quadWithTextureMapping({{"wrapT", "REPEAT"}}, json::object()).writeGltf(directory / "text.gltf"),
                    {"samplers[0].wrapT", "expected an integer"});
    expectLoadError(quadWithTextureMapping(json::object(), {1, 2}).writeGltf(directory / "array.gltf"),
                    {field, "expected an object"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"offset", json::array()}}).writeGltf(directory / "e.gltf"),
                    {field + ".offset", "is empty"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"rotation", json::object()}}).writeGltf(directory / "r.gltf"),
                    {field + ".rotation", "is empty"});
    expectLoadError(quadWithTextureMapping(json::object(), {{"texCoord", 0.5}}).writeGltf(directory / "t.gltf"),
                    {field + ".texCoord", "expected an index"});
}

// A floor and the KHR_lights_punctual definitions `lights`, light 0 placed by a node.
GltfBuilder floorWithLights(json lights, json placement = {{"light", 0}}) {
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f))}});
    builder.document()["extensions"]["KHR_lights_punctual"]["lights"] = std::move(lights);
    builder.addNode({{"extensions", {{"KHR_lights_punctual", std::move(placement)}}}});
    return builder;
}

// tinygltf drops a null, an empty {} in an extension and a non-object extension, and
// ignores a vector of the wrong length or a negative index: each would leave a default in
// the file's place without a word. The loader refuses them, naming the field.
TEST(LoadSceneErrors, WhatTinygltfWouldDropIsRefusedNamingTheField) {
    TemporaryDirectory directory;
    const std::string medium = "materials[0].extensions.VKDR_participating_media";
    expectLoadError(boxWithMaterial(mediumMaterial({{"sigma_a", nullptr}})).writeGltf(directory / "null.gltf"),
                    {medium + ".sigma_a", "null is not a glTF value"});
    expectLoadError(boxWithMaterial(mediumMaterial({{"sigma_s", json::object()}})).writeGltf(directory / "empty.gltf"),
                    {medium + ".sigma_s", "is empty ({})"});
    expectLoadError(boxWithMaterial(mediumMaterial({{"emission", json::array()}})).writeGltf(directory / "none.gltf"),
                    {medium + ".emission", "is empty ([])"});
    expectLoadError(boxWithMaterial(mediumMaterial({1.0, 2.0})).writeGltf(directory / "array.gltf"),
                    {medium, "expected an object, got [1.0,2.0]"});
    json threeEntries = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5}}}}};
    expectLoadError(boxWithMaterial(threeEntries).writeGltf(directory / "colour.gltf"),
                    {"materials[0].pbrMetallicRoughness.baseColorFactor", "expected an array of 4 numbers"});
    expectLoadError(boxWithMaterial({{"emissiveFactor", "red"}}).writeGltf(directory / "emissive.gltf"),
                    {"materials[0].emissiveFactor", "expected an array of 3 numbers, got \"red\""});

    GltfBuilder scene = boxWithMaterial({{"name", "white"}});
    scene.document()["extensions"]["KHR_lights_punctual"] = {{"lights", {{"type", "point"}}}};
    expectLoadError(scene.writeGltf(directory / "lights.gltf"), {"extensions.KHR_lights_punctual.lights",
                                                                 "expected an array"});
}

// A 2.0 reader reads any 2.x file unless its minVersion asks for more.
TEST(LoadSceneErrors, GltfVersionsOtherThanTwo) {
    TemporaryDirectory directory;
    auto boxOfVersion = [](json asset) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        builder.document()["asset"] = std::move(asset);
        return builder;
    };
    expectLoadError(boxOfVersion({{"version", "1.0"}}).writeGltf(directory / "one.gltf"),
                    {"asset.version", "glTF 1.0 is not supported; the loader reads glTF 2.x"});
    expectLoadError(boxOfVersion({{"version", "3.0"}}).writeGltf(directory / "three.gltf"),
                    {"asset.version", "glTF 3.0 is not supported"});
    expectLoadError(boxOfVersion({{"version", "2"}}).writeGltf(directory / "bare.gltf"),
                    {"asset.version", "expected a version such as \"2.0\", got \"2\""});
    expectLoadError(boxOfVersion({{"version", "2.1"}, {"minVersion", "2.5"}}).writeGltf(directory / "min.gltf"),
                    {"asset.minVersion", "the file needs a glTF 2.5 reader; the loader implements glTF 2.0"});
    expectLoadError(boxOfVersion({{"version", "2.0"}, {"minVersion", "two"}}).writeGltf(directory / "word.gltf"),
                    {"asset.minVersion", "expected a version such as \"2.0\""});
    const GltfBuilder later = boxOfVersion({{"version", "2.1"}, {"minVersion", "2.0"}});
    EXPECT_NO_THROW(loadScene(later.writeGltf(directory / "later.gltf")));
}

// A buffer's data URI may be megabytes: a message names the field and quotes its start.
TEST(LoadSceneErrors, DataUriProblemsDoNotQuoteTheData) {
    TemporaryDirectory directory;
    GltfBuilder builder = boxWithMaterial({{"name", "white"}});
    const json original = json::parse(builder.gltfText());
    const std::string uri = original["buffers"][0]["uri"];
    auto withBuffer = [&](const std::string& newUri, size_t byteLength) {
        json document = original;
        document["buffers"][0] = {{"uri", newUri}, {"byteLength", byteLength}};
        return writeText(directory / "buffer.gltf", document.dump());
    };
    const size_t bytes = original["buffers"][0]["byteLength"];
    expectLoadError(withBuffer(uri, bytes + 4),
                    {"buffers[0].byteLength", "but the data URI holds " + std::to_string(bytes) + " bytes"});
    const std::string prefix = "data:application/octet-stream;base64,";
    expectLoadError(withBuffer(prefix + "AA!A", 3), {"buffers[0].uri", "has '!' at character 3"});
    expectLoadError(withBuffer(prefix + "AAA", 2), {"buffers[0].uri", "not a whole number of 4-character groups"});
    expectLoadError(withBuffer(prefix, 0), {"buffers[0].uri", "holds no data"});
    // A media type tinygltf does not read: named by its header, without the data.
    const std::string unknownType = "data:foo/bar;base64," + uri.substr(prefix.size());
    try {
        loadScene(withBuffer(unknownType, bytes));
        ADD_FAILURE() << "a data URI of an unknown media type loaded";
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("buffers[0].uri: a data URI is read in base64, with the media type "
                               "application/octet-stream"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find("this one starts 'data:foo/bar;base64'"), std::string::npos) << message;
        EXPECT_EQ(message.find(unknownType.substr(40)), std::string::npos) << message;
    }
}

// tinygltf reads a negative index as "none" (a primitive's material -1 as the default
// material) and a fractional or text one as something else again.
TEST(LoadSceneErrors, IndicesThatAreNotWholeNumbersAreRefusedEverywhere) {
    TemporaryDirectory directory;
    auto changed = [&](const std::function<void(json&)>& change) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        change(builder.document());
        return builder.writeGltf(directory / "index.gltf");
    };
    const std::string expected = "expected an index (an integer from 0 to 2147483647, without a decimal point)";
    expectLoadError(changed([](json& d) { d["scene"] = -1; }), {"scene", expected + ", got -1"});
    expectLoadError(changed([](json& d) { d["scene"] = 0.5; }), {"scene", expected});
    expectLoadError(changed([](json& d) { d["scene"] = "0"; }), {"scene", expected});
    // tinygltf reads neither 0.0 nor a number beyond int's range as the index it means.
    expectLoadError(changed([](json& d) { d["scene"] = 0.0; }), {"scene", expected + ", got 0.0"});
    expectLoadError(changed([](json& d) { d["nodes"][0]["mesh"] = int64_t(1) << 32; }),
                    {"nodes[0].mesh", expected + ", got 4294967296"});
    expectLoadError(changed([](json& d) { d["scenes"] = {{{"nodes", {-1}}}}; }), {"scenes[0].nodes[0]", expected});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["material"] = -1; }),
                    {"meshes[0].primitives[0].material", expected});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["indices"] = -1; }),
                    {"meshes[0].primitives[0].indices", expected});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 1.5; }),
                    {"meshes[0].primitives[0].attributes.POSITION", expected});
    expectLoadError(changed([](json& d) { d["accessors"][0]["bufferView"] = -2; }),
                    {"accessors[0].bufferView", expected});
    expectLoadError(changed([](json& d) { d["bufferViews"][0]["buffer"] = -1; }), {"bufferViews[0].buffer", expected});
    expectLoadError(changed([](json& d) { d["materials"][0]["emissiveTexture"] = {{"index", -1}}; }),
                    {"materials[0].emissiveTexture.index", expected});
    // Offsets and modes tinygltf would read as their defaults: vertices from another
    // part of the buffer, or triangles instead of a strip.
    const std::string whole = "expected an integer from 0 to";
    expectLoadError(changed([](json& d) { d["accessors"][0]["byteOffset"] = -12; }),
                    {"accessors[0].byteOffset", whole, "got -12"});
    expectLoadError(changed([](json& d) { d["accessors"][0]["byteOffset"] = "12"; }),
                    {"accessors[0].byteOffset", whole});
    expectLoadError(changed([](json& d) { d["bufferViews"][0]["byteOffset"] = 1.5; }),
                    {"bufferViews[0].byteOffset", whole});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["mode"] = "5"; }),
                    {"meshes[0].primitives[0].mode", whole});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["mode"] = -1; }),
                    {"meshes[0].primitives[0].mode", whole});
    for (const json& stride : {json(-12), json("12"), json(2), json(300), json(14)}) {
        expectLoadError(changed([&](json& d) { d["bufferViews"][0]["byteStride"] = stride; }),
                        {"bufferViews[0].byteStride", "must be a multiple of 4 from 4 to 252"});
    }
    // Offsets between components: the floats would be read from the bytes of two.
    expectLoadError(changed([](json& d) { d["accessors"][0]["byteOffset"] = 2; }),
                    {"accessors[0].byteOffset", "2 is not a multiple of the 4-byte components of accessors[0]"});
    expectLoadError(changed([](json& d) {
                        d["bufferViews"][0]["byteOffset"] = 2;
                        d["bufferViews"][0]["byteLength"] = d["bufferViews"][0]["byteLength"].get<int>() - 4;
                    }),
                    {"bufferViews[0].byteOffset", "2 is not a multiple of the 4-byte components of accessors["});
    // Valid glTF that the loader does not read: an accessor of zeros, without a buffer view.
    expectLoadError(changed([](json& d) { d["accessors"][0].erase("bufferView"); }), {"accessors[0]", "no bufferView"});
}

// tinygltf reads a member of the wrong JSON type as absent: a primitive would vanish, a
// light's intensity or a material's doubleSided would silently take its default.
TEST(LoadSceneErrors, MembersOfTheWrongJsonTypeAreRefusedNamingTheField) {
    TemporaryDirectory directory;
    auto changed = [&](const std::function<void(json&)>& change) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        change(builder.document());
        return builder.writeGltf(directory / "kind.gltf");
    };
    const std::string primitive = "meshes[0].primitives[0]";
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"] = {5}; }),
                    {primitive, "expected an object, got 5"});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"] = {json::object()}; }),
                    {primitive + ".attributes", "missing; glTF requires it"});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["attributes"] = 5; }),
                    {primitive + ".attributes", "expected an object, got 5"});
    expectLoadError(changed([](json& d) { d["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }),
                    {primitive + ".attributes", "no POSITION attribute"});
    expectLoadError(changed([](json& d) { d["nodes"].push_back(5); }), {"nodes[1]", "expected an object, got 5"});
    expectLoadError(changed([](json& d) { d["scenes"][0]["nodes"] = "0"; }),
                    {"scenes[0].nodes", "expected an array, got \"0\""});
    expectLoadError(changed([](json& d) { d["extensionsRequired"] = "KHR_draco_mesh_compression"; }),
                    {"extensionsRequired", "expected an array"});
    expectLoadError(changed([](json& d) { d["extensionsUsed"] = {5}; }), {"extensionsUsed[0]", "expected a string"});
    expectLoadError(changed([](json& d) { d["materials"][0]["doubleSided"] = "true"; }),
                    {"materials[0].doubleSided", "expected true or false, got \"true\""});
    expectLoadError(changed([](json& d) { d["materials"][0]["pbrMetallicRoughness"] = json::array(); }),
                    {"materials[0].pbrMetallicRoughness", "expected an object, got []"});
    expectLoadError(changed([](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = 0; }),
                    {"materials[0].pbrMetallicRoughness.baseColorTexture", "expected an object, got 0"});
    expectLoadError(changed([](json& d) {
                        d["cameras"] = {{{"type", "orthographic"},
                                         {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", "0"}, {"zfar", 9}}}}};
                    }),
                    {"cameras[0].orthographic.znear", "expected a number"});
    const std::string light = "extensions.KHR_lights_punctual.lights[0]";
    auto withLight = [&](json source) {
        return changed([&](json& d) { d["extensions"]["KHR_lights_punctual"] = {{"lights", {source}}}; });
    };
    expectLoadError(withLight({{"type", "point"}, {"intensity", "5"}}),
                    {light + ".intensity", "expected a number, got \"5\""});
    expectLoadError(withLight({{"type", "point"}, {"color", "red"}}), {light + ".color", "expected an array of 3"});
    expectLoadError(withLight({{"type", "spot"}, {"spot", {{"outerConeAngle", "0.3"}}}}),
                    {light + ".spot.outerConeAngle", "expected a number"});
    expectLoadError(withLight({{"type", "spot"}, {"spot", "wide"}}), {light + ".spot", "expected an object"});
    expectLoadError(withLight({{"type", "spot"}}), {light + ":", "type \"spot\" needs a \"spot\" object"});
}

TEST(LoadSceneErrors, NodesOutsideTheGltfSchema) {
    TemporaryDirectory directory;
    auto boxAt = [&](json node) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        builder.document()["nodes"][0].update(node);
        return builder.writeGltf(directory / "node.gltf");
    };
    expectLoadError(boxAt({{"mesh", -1}}), {"nodes[0].mesh", "expected an index (an integer from 0 to 2147483647, without a decimal point), got -1"});
    expectLoadError(boxAt({{"children", {0.5}}}), {"nodes[0].children[0]", "expected an index"});
    expectLoadError(boxAt({{"translation", {1.0, 2.0}}}), {"nodes[0].translation", "expected an array of 3 numbers"});
    expectLoadError(boxAt({{"scale", 2.0}}), {"nodes[0].scale", "expected an array of 3 numbers, got 2.0"});
    expectLoadError(boxAt({{"matrix", {1.0, 0.0, 0.0}}}), {"nodes[0].matrix", "expected an array of 16 numbers"});
    json projective = {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.5, 0.0, 0.0, 0.0, 1.0};
    expectLoadError(boxAt({{"matrix", projective}}), {"nodes[0].matrix", "must be affine", "got 0.0 0.0 0.5 1.0"});
    const json identity = {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    expectLoadError(boxAt({{"matrix", identity}, {"scale", {2.0, 2.0, 2.0}}}),
                    {"nodes[0].scale", "a node with a matrix must not have a translation, rotation or scale"});
    expectLoadError(boxAt({{"rotation", {0.0, 0.0, 0.0, 0.0}}}),
                    {"nodes[0].rotation", "must be a unit quaternion", "got length 0"});
    expectLoadError(boxAt({{"rotation", {0.0, 0.0, 0.0, 2.0}}}), {"nodes[0].rotation", "got length 2"});
    // An exporter's float rounding of a unit quaternion loads.
    const float half = std::sqrt(0.5f);
    Scene turned = loadScene(boxAt({{"rotation", {0.0, half, 0.0, half}}})).scene;
    EXPECT_EQ(turned.triangles.size(), 12u);

    GltfBuilder hollow = boxWithMaterial({{"name", "white"}});
    hollow.document()["meshes"].push_back({{"name", "nothing"}, {"primitives", json::array()}});
    hollow.addNode({{"mesh", 1}});
    expectLoadError(hollow.writeGltf(directory / "hollow.gltf"), {"meshes[1].primitives", "at least one primitive"});
}

TEST(LoadSceneErrors, CamerasOutsideTheGltfSchema) {
    TemporaryDirectory directory;
    auto withCamera = [&](json perspective) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        json base = {{"yfov", 0.8}, {"znear", 0.01}};
        base.update(perspective);
        builder.addNode({{"camera", builder.addCamera({{"type", "perspective"}, {"perspective", base}})}});
        return builder.writeGltf(directory / "camera.gltf");
    };
    const std::string field = "cameras[0].perspective";
    expectLoadError(withCamera({{"aspectRatio", 0.0}}), {field + ".aspectRatio", "must be a number > 0, got 0.0"});
    expectLoadError(withCamera({{"znear", 0.0}}), {field + ".znear", "must be a number > 0"});
    expectLoadError(withCamera({{"znear", -1.0}}), {field + ".znear", "got -1.0"});
    expectLoadError(withCamera({{"zfar", 0.001}}), {field + ".zfar", "must be a number > znear (0.01), got 0.001"});
    EXPECT_EQ(loadScene(withCamera({{"zfar", 100.0}, {"aspectRatio", 1.5}})).scene.cameras.at(0).aspectRatio, 1.5f);
    // Just under pi as a double is pi as the float the renderer takes, and a tiny one is
    // 0: refused here, not by the render after the load accepted it.
    expectLoadError(withCamera({{"yfov", 3.14159265}}), {field + ".yfov", "must be in (0, pi) as a float"});
    expectLoadError(withCamera({{"yfov", 1e-50}}), {field + ".yfov", "must be in (0, pi) as a float, got 1e-50"});
    EXPECT_LT(loadScene(withCamera({{"yfov", 3.1415}})).scene.cameras.at(0).yfov, std::numbers::pi_v<float>);
}

// glTF requires xmag and ymag other than 0 and a zfar beyond znear >= 0; negative
// magnifications (a mirrored view) are refused too.
TEST(LoadSceneErrors, OrthographicCamerasWithoutAView) {
    TemporaryDirectory directory;
    auto withCamera = [&](json orthographic) {
        GltfBuilder builder = boxWithMaterial({{"name", "white"}});
        json base = {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.0}, {"zfar", 10.0}};
        base.update(orthographic);
        builder.addNode({{"camera", builder.addCamera({{"type", "orthographic"}, {"orthographic", base}})}});
        return builder.writeGltf(directory / "camera.gltf");
    };
    const std::string field = "cameras[0].orthographic";
    expectLoadError(withCamera({{"xmag", 0.0}}), {field + ".xmag", "must be a number > 0, got 0.0"});
    expectLoadError(withCamera({{"ymag", -2.0}}), {field + ".ymag", "got -2"});
    expectLoadError(withCamera({{"ymag", 1e39}}), {field + ".ymag", "a normal float"});
    // A subnormal float, which a device may flush to 0 (no orthographic camera then).
    expectLoadError(withCamera({{"xmag", 1e-39}, {"ymag", 1e-39}}), {field + ".xmag", "a normal float"});
    expectLoadError(withCamera({{"xmag", 1e5}}), {field, "xmag / ymag must be in [1e-4, 1e4], got 1e+05"});
    expectLoadError(withCamera({{"znear", -1.0}}), {field + ".znear", "must be >= 0"});
    expectLoadError(withCamera({{"znear", 2.0}, {"zfar", 1.0}}), {field + ".zfar", "must be a number > znear (2)"});
    const Camera camera = loadScene(withCamera({{"xmag", 3.0}, {"ymag", 1.5}})).scene.cameras.at(0);
    EXPECT_EQ(camera.orthographicHalfHeight, 1.5f);
    EXPECT_EQ(camera.aspectRatio, 2.0f);
}

// A member of vkdiffrender's own extensions that the loader does not know (a misspelling,
// say) is ignored with a warning naming it and the members it knows.
TEST(LoadSceneErrors, UnknownMediumMembersAreNamedInAWarning) {
    TemporaryDirectory directory;
    LoadedScene loaded = loadScene(
        boxWithMaterial(mediumMaterial({{"sigma_s", 1.0}, {"sigma_t", 2.0}})).writeGltf(directory / "typo.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("materials[0].extensions.VKDR_participating_media.sigma_t: unknown member, "
                                      "ignored (known: sigma_a, sigma_s, g, emission"),
              std::string::npos)
        << loaded.warnings[0];
    EXPECT_EQ(loaded.scene.media.at(0).sigma_s, glm::vec3(1.0f));
}

// glTF's volume lies behind a transmissive surface: without KHR_materials_transmission the
// surface is opaque, and the volume a viewer would not show either is warned of.
TEST(LoadSceneErrors, AVolumeWithoutTransmissionIsWarnedOf) {
    TemporaryDirectory directory;
    json material = {{"name", "smoke"},
                     {"extensions",
                      {{"KHR_materials_volume", {{"attenuationColor", {0.5, 0.5, 0.5}}, {"attenuationDistance", 1.0}}}}}};
    LoadedScene loaded = loadScene(boxWithMaterial(material).writeGltf(directory / "volume.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("materials[0].extensions.KHR_materials_volume: ignored: without "
                                      "KHR_materials_transmission"),
              std::string::npos)
        << loaded.warnings[0];
    EXPECT_TRUE(loaded.scene.media.empty());
}

// A medium boundary passes rays through and emits nothing: an emissiveFactor on its
// material, which a glTF viewer would show glowing, is ignored with a warning.
TEST(LoadSceneErrors, EmissionOnAMediumBoundaryIsWarnedOf) {
    TemporaryDirectory directory;
    json material = mediumMaterial({{"sigma_s", 1.0}});
    material["emissiveFactor"] = {1.0, 0.5, 0.0};
    LoadedScene loaded = loadScene(boxWithMaterial(material).writeGltf(directory / "glow.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("materials[0]: a medium boundary does not emit"), std::string::npos)
        << loaded.warnings[0];
    material["emissiveFactor"] = {0.0, 0.0, 0.0};
    EXPECT_TRUE(loadScene(boxWithMaterial(material).writeGltf(directory / "dark.gltf")).warnings.empty());
}

// COLOR_0 multiplies the base colour, which must stay in [0, 1]: a colour outside it
// (here the box's positions, -1 to 1) is refused, naming the vertex and channel.
TEST(LoadSceneErrors, VertexColoursOutsideZeroToOne) {
    TemporaryDirectory directory;
    GltfBuilder gltf;
    gltf.addNode({{"mesh", gltf.addMesh("box", box(glm::vec3(-1.0f), glm::vec3(1.0f)))}});
    json& attributes = gltf.document()["meshes"][0]["primitives"][0]["attributes"];
    attributes["COLOR_0"] = attributes["POSITION"];
    expectLoadError(gltf.writeGltf(directory / "colours.gltf"),
                    {"meshes[0].primitives[0].attributes.COLOR_0", "colour 0 has R = -1; must be in [0, 1]"});
}

// Plain integers (KHR_mesh_quantization's) would otherwise be read as normalized ones.
TEST(LoadSceneErrors, IntegerTextureCoordinatesAndColoursMustBeNormalized) {
    TemporaryDirectory directory;
    for (const char* attribute : {"TEXCOORD_0", "COLOR_0"}) {
        for (int componentType : {5121, 5123}) {
            SCOPED_TRACE(std::string(attribute) + " " + std::to_string(componentType));
            GltfBuilder gltf;
            gltf.addNode({{"mesh", gltf.addMesh("quad", floorQuad(1.0f))}});
            const int view = gltf.addBufferView(std::vector<unsigned char>(4 * 4 * 2, 1));
            gltf.document()["accessors"].push_back({{"bufferView", view},
                                                    {"componentType", componentType},
                                                    {"count", 4},
                                                    {"type", std::string(attribute) == "COLOR_0" ? "VEC4" : "VEC2"}});
            const size_t accessor = gltf.document()["accessors"].size() - 1;
            gltf.document()["meshes"][0]["primitives"][0]["attributes"][attribute] = accessor;
            expectLoadError(gltf.writeGltf(directory / "integers.gltf"),
                            {"accessors[" + std::to_string(accessor) + "].normalized",
                             std::string("integer components of meshes[0].primitives[0].attributes.") + attribute +
                                 " must be normalized"});
        }
    }
}

// glTF gives a node one place; a node listed in several is rendered at each, and said.
TEST(LoadSceneErrors, ANodeListedTwiceIsNamedInAWarning) {
    TemporaryDirectory directory;
    GltfBuilder gltf;
    gltf.addNode({{"mesh", gltf.addMesh("box", box(glm::vec3(-1.0f), glm::vec3(1.0f)))}});
    gltf.document()["scenes"][0]["nodes"] = {0, 0};
    LoadedScene loaded = loadScene(gltf.writeGltf(directory / "twice.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("nodes[0]: listed 2 times"), std::string::npos) << loaded.warnings[0];
    EXPECT_EQ(loaded.scene.triangles.size(), 24u);

    gltf.document()["scenes"][0]["nodes"] = {1, 2};
    gltf.document()["nodes"].push_back({{"children", {0}}});
    gltf.document()["nodes"].push_back({{"children", {0}}, {"translation", {3.0, 0.0, 0.0}}});
    loaded = loadScene(gltf.writeGltf(directory / "two_parents.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("nodes[0]: listed 2 times"), std::string::npos) << loaded.warnings[0];
}

TEST(LoadSceneErrors, PunctualLightsAreCheckedFieldByField) {
    TemporaryDirectory directory;
    const std::string lights = "extensions.KHR_lights_punctual.lights[0]";
    expectLoadError(floorWithLights({{{"type", "area"}}}).writeGltf(directory / "type.gltf"),
                    {lights + ".type", "expected \"point\", \"spot\" or \"directional\", got \"area\""});
    expectLoadError(floorWithLights({{{"type", "point"}, {"intensity", -1.0}}}).writeGltf(directory / "negative.gltf"),
                    {lights + ".intensity", "must be a finite number >= 0"});
    expectLoadError(floorWithLights({{{"type", "point"}, {"color", {1.0, -0.5, 1.0}}}}).writeGltf(directory / "c.gltf"),
                    {lights + ".color[1]", "must be >= 0"});
    expectLoadError(floorWithLights({{{"type", "point"}, {"intensity", 1e13}}}).writeGltf(directory / "bright.gltf"),
                    {lights, "color x intensity must be in [0, 1e+12]"});
    // Beyond float's range: named as too bright (not as NaN), and dark where the colour is 0.
    expectLoadError(floorWithLights({{{"type", "point"}, {"intensity", 1e300}, {"color", {0.0, 1.0, 0.0}}}})
                        .writeGltf(directory / "huge.gltf"),
                    {lights, "color x intensity must be in [0, 1e+12], got 1e+300"});
    EXPECT_EQ(loadScene(floorWithLights({{{"type", "point"}, {"intensity", 1e300}, {"color", {0.0, 0.0, 0.0}}}})
                            .writeGltf(directory / "dark.gltf"))
                  .scene.punctualLights.at(0)
                  .intensity,
              glm::vec3(0.0f));
    expectLoadError(floorWithLights({{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}}})
                        .writeGltf(directory / "cones.gltf"),
                    {lights + ".spot.innerConeAngle", "must be in [0, outerConeAngle"});
    expectLoadError(floorWithLights({{{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}}})
                        .writeGltf(directory / "wide.gltf"),
                    {lights + ".spot.outerConeAngle", "must be in (0, pi/2]"});
    expectLoadError(floorWithLights({{{"type", "point"}, {"name", "a"}}, {{"type", "point"}, {"name", "a"}}})
                        .writeGltf(directory / "names.gltf"),
                    {"extensions.KHR_lights_punctual.lights[1].name", "'a' already names", "must be unique"});
    expectLoadError(floorWithLights({{{"type", "point"}}}, {{"light", 3}}).writeGltf(directory / "index.gltf"),
                    {"nodes[1].extensions.KHR_lights_punctual.light", "light 3 out of range (1 lights)"});
    // An index is written without a decimal point, as every other index of the file.
    expectLoadError(floorWithLights({{{"type", "point"}}}, {{"light", 0.0}}).writeGltf(directory / "decimal.gltf"),
                    {"nodes[1].extensions.KHR_lights_punctual.light", "expected an index", "without a decimal point"});
}

// Members tinygltf reads as -1 when absent are named as missing, not as "-1".
TEST(LoadSceneErrors, AbsentIndicesAreNamedAsMissing) {
    TemporaryDirectory directory;
    GltfBuilder sourceless = quadWithTextureMapping(json::object(), json::object());
    sourceless.document()["textures"][0].erase("source");
    expectLoadError(sourceless.writeGltf(directory / "sourceless.gltf"), {"textures[0]: has no source image"});
    expectLoadError(floorWithLights({{{"type", "point"}}}, json::object()).writeGltf(directory / "lightless.gltf"),
                    {"nodes[1].extensions.KHR_lights_punctual: has no \"light\""});
}

// An unnamed light whose index-name another light has as its own gets '_' appended, as
// a material or camera does, with a warning.
TEST(LoadSceneErrors, AnUnnamedLightTakesANameNoOtherLightHas) {
    TemporaryDirectory directory;
    LoadedScene loaded = loadScene(floorWithLights({{{"type", "point"}, {"name", "lights[1]"}}, {{"type", "point"}}})
                                       .writeGltf(directory / "names.gltf"));
    ASSERT_EQ(loaded.scene.punctualLights.size(), 2u);
    EXPECT_EQ(loaded.scene.punctualLights[0].name, "lights[1]");
    EXPECT_EQ(loaded.scene.punctualLights[1].name, "lights[1]_");
    std::string all;
    for (const std::string& warning : loaded.warnings) all += warning + "\n";
    EXPECT_NE(all.find("KHR_lights_punctual.lights[1]: unnamed, and 'lights[1]' is another light's name; this one "
                       "is named 'lights[1]_'"),
              std::string::npos)
        << all;
}

TEST(LoadSceneErrors, PunctualLightWarnings) {
    TemporaryDirectory directory;
    const std::filesystem::path file =
        floorWithLights({{{"type", "point"}, {"range", 5.0}}, {{"type", "point"}, {"name", "unplaced"}}})
            .writeGltf(directory / "warnings.gltf");
    LoadedScene loaded = loadScene(file);
    ASSERT_EQ(loaded.scene.punctualLights.size(), 2u);
    EXPECT_EQ(loaded.scene.punctualLights[0].name, "lights[0]");  // unnamed
    ASSERT_EQ(loaded.scene.lightPlacements.size(), 1u);
    std::string all;
    for (const std::string& warning : loaded.warnings) {
        all += warning + "\n";
    }
    EXPECT_NE(all.find("lights[0].range: ignored"), std::string::npos) << all;
    const std::vector<std::string> sceneChecks = sceneWarnings(loaded.scene, file);
    ASSERT_EQ(sceneChecks.size(), 1u);
    EXPECT_EQ(sceneChecks[0], file.string() + ": light 'unplaced' is placed by no node and lights nothing");
    // glTF wants a range above 0; one at or below is no more used, 0 included (which
    // tinygltf reads for an absent range).
    for (double range : {-1.0, 0.0}) {
        loaded = loadScene(floorWithLights({{{"type", "point"}, {"range", range}}}).writeGltf(directory / "low.gltf"));
        ASSERT_EQ(loaded.warnings.size(), 1u) << "range " << range;
        EXPECT_NE(loaded.warnings[0].find("lights[0].range: ignored"), std::string::npos) << loaded.warnings[0];
    }
    loaded = loadScene(floorWithLights({{{"type", "point"}}}).writeGltf(directory / "none.gltf"));
    EXPECT_TRUE(loaded.warnings.empty());
}

}  // namespace
}  // namespace vkdr::test
