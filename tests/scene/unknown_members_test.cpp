// A member that glTF's schema does not define is skipped by tinygltf; a misspelt one
// would leave a default in its place without a word. The loader warns, naming it and
// the members the object has.
#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

// The one warning of `loaded`, which must name `field` and say it is unknown.
void expectOneUnknownMember(const LoadedScene& loaded, const std::string& field, const std::string& known) {
    ASSERT_EQ(loaded.warnings.size(), 1u) << (loaded.warnings.empty() ? "" : loaded.warnings[0]);
    EXPECT_NE(loaded.warnings[0].find(": " + field + ": unknown member, ignored (glTF's: " + known + ")"),
              std::string::npos)
        << loaded.warnings[0];
}

GltfBuilder litFloor(json light, json placement = {{"light", 0}}) {
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f))}});
    builder.document()["extensions"]["KHR_lights_punctual"]["lights"] = {std::move(light)};
    builder.addNode({{"translation", {0.0, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", std::move(placement)}}}});
    return builder;
}

TEST(UnknownMembers, AMisspeltLightMemberIsWarnedOfAndTheDefaultStays) {
    TemporaryDirectory directory;
    const std::string light = "extensions.KHR_lights_punctual.lights[0]";
    LoadedScene loaded = loadScene(
        litFloor({{"type", "point"}, {"intensty", 5.0}}).writeGltf(directory / "intensity.gltf"));
    expectOneUnknownMember(loaded, light + ".intensty", "name, color, intensity, type, range, spot");
    EXPECT_EQ(loaded.scene.punctualLights.at(0).intensity, glm::vec3(1.0f));

    loaded = loadScene(litFloor({{"type", "spot"}, {"spot", {{"outerCone", 0.3}}}}).writeGltf(directory / "spot.gltf"));
    expectOneUnknownMember(loaded, light + ".spot.outerCone", "innerConeAngle, outerConeAngle");

    GltfBuilder misplaced = litFloor({{"type", "point"}}, {{"light", 0}, {"lamp", 1}});
    loaded = loadScene(misplaced.writeGltf(directory / "node.gltf"));
    expectOneUnknownMember(loaded, "nodes[1].extensions.KHR_lights_punctual.lamp", "light");

    GltfBuilder misplacedList = litFloor({{"type", "point"}});
    misplacedList.document()["extensions"]["KHR_lights_punctual"]["light"] = json::array();
    loaded = loadScene(misplacedList.writeGltf(directory / "list.gltf"));
    expectOneUnknownMember(loaded, "extensions.KHR_lights_punctual.light", "lights");
}

TEST(UnknownMembers, MisspeltMembersOfCoreObjectsAreWarnedOf) {
    TemporaryDirectory directory;
    auto loadWith = [&](const std::function<void(json&)>& change) {
        GltfBuilder builder;
        const int material = builder.addMaterial({{"name", "grey"}});
        builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), material)}});
        builder.addNode({{"camera", builder.addCamera({{"type", "perspective"},
                                                       {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}})},
                         {"translation", {0.5, 0.5, 4.0}}});
        change(builder.document());
        return loadScene(builder.writeGltf(directory / "scene.gltf"));
    };
    const LoadedScene colour = loadWith([](json& document) {
        document["materials"][0]["pbrMetallicRoughness"]["baseColorFactr"] = {0.1, 0.2, 0.3, 1.0};
    });
    expectOneUnknownMember(colour, "materials[0].pbrMetallicRoughness.baseColorFactr",
                           "baseColorFactor, baseColorTexture, metallicFactor, roughnessFactor, "
                           "metallicRoughnessTexture");
    expectOneUnknownMember(loadWith([](json& document) { document["materials"][0]["doubleSide"] = true; }),
                           "materials[0].doubleSide",
                           "name, pbrMetallicRoughness, normalTexture, occlusionTexture, emissiveTexture, "
                           "emissiveFactor, alphaMode, alphaCutoff, doubleSided");
    expectOneUnknownMember(loadWith([](json& document) { document["nodes"][1]["translate"] = {0, 0, 1}; }),
                           "nodes[1].translate",
                           "camera, children, skin, matrix, mesh, rotation, scale, translation, weights, name");
    expectOneUnknownMember(loadWith([](json& document) { document["cameras"][0]["perspective"]["fov"] = 1.0; }),
                           "cameras[0].perspective.fov", "aspectRatio, yfov, zfar, znear");
    expectOneUnknownMember(loadWith([](json& document) { document["meshes"][0]["primitives"][0]["materal"] = 0; }),
                           "meshes[0].primitives[0].materal", "attributes, indices, material, mode, targets");
    expectOneUnknownMember(loadWith([](json& document) { document["accessors"][0]["normalised"] = false; }),
                           "accessors[0].normalised",
                           "bufferView, byteOffset, componentType, normalized, count, type, max, min, sparse, name");
    expectOneUnknownMember(loadWith([](json& document) { document["asset"]["author"] = "someone"; }),
                           "asset.author", "copyright, generator, version, minVersion");
    const LoadedScene root = loadWith([](json& document) { document["scen"] = 0; });
    ASSERT_EQ(root.warnings.size(), 1u);
    EXPECT_NE(root.warnings[0].find(": scen: unknown member, ignored"), std::string::npos) << root.warnings[0];
}

// Every member the schema defines, extensions and extras anywhere: no warning.
TEST(UnknownMembers, TheSchemasMembersAndExtrasAreNotWarnedOf) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    const int material = builder.addMaterial(
        {{"name", "grey"},
         {"extras", {{"note", 1}}},
         {"doubleSided", false},
         {"alphaCutoff", 0.5},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0},
                                   {"roughnessFactor", 1.0}, {"extras", json::object()}}}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), material)},
                     {"name", "box"},
                     {"scale", {1, 1, 1}},
                     {"extras", {{"anything", "goes"}}}});
    builder.document()["asset"]["copyright"] = "public domain";
    builder.document()["asset"]["extras"] = json::object();
    builder.document()["extras"] = {{"tool", "test"}};
    builder.document()["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "spot"}, {"name", "lamp"}, {"color", {1, 1, 1}}, {"intensity", 2.0},
         {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}}};
    builder.addNode({{"translation", {0.5, 3.0, 0.5}},
                     {"rotation", {-0.70710678, 0.0, 0.0, 0.70710678}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const LoadedScene loaded = loadScene(builder.writeGltf(directory / "scene.gltf"));
    EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
}

TEST(UnknownMembers, AnAlphaModeThatIsNotGltfsIsNamed) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    const int material = builder.addMaterial({{"name", "glass"}, {"alphaMode", "TRANSPARENT"}});
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), material)}});
    const LoadedScene loaded = loadScene(builder.writeGltf(directory / "alpha.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("materials[0].alphaMode: 'TRANSPARENT' is not one of glTF's alpha modes "
                                      "(OPAQUE, MASK, BLEND); the surface is opaque"),
              std::string::npos)
        << loaded.warnings[0];
}

}  // namespace
}  // namespace vkdr::test
