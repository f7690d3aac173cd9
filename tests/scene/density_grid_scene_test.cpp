// Density grids referenced from glTF: placement by the grid's own transform and a node's,
// on materials and the scene medium; the grid files among the files read, and the
// fitted voxels in the grid a written scene refers to; and one error naming the field for each kind of bad reference.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"
#include "scene/write_scene.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

DensityGrid smallGrid() {
    DensityGrid grid;
    grid.name = "density";
    grid.firstVoxel = glm::ivec3(-1, 0, 2);
    grid.size = glm::ivec3(2, 3, 1);
    grid.values = {0.0f, 1.0f, 2.0f, 0.5f, 0.25f, 3.0f};
    grid.indexToLocal = glm::dmat4(glm::dvec4(0.1, 0, 0, 0), glm::dvec4(0, 0.2, 0, 0), glm::dvec4(0, 0, 0.1, 0),
                                   glm::dvec4(-0.5, 0.25, 0.0, 1.0));
    return grid;
}

json gridMedium(json density) {
    return {{"name", "smoke"},
            {"extensions", {{"VKDR_participating_media", {{"sigma_s", 2.0}, {"density", std::move(density)}}}}}};
}

// A box enclosing the medium of `material`, and an empty node placed at (1, 2, 3),
// scaled by 2 and turned a quarter about y (node 1).
GltfBuilder boxScene(json material, double placementScale = 2.0) {
    GltfBuilder builder;
    int index = builder.addMaterial(std::move(material));
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}), index)}});
    builder.addNode({{"translation", {1.0, 2.0, 3.0}},
                     {"rotation", {0.0, std::sqrt(0.5), 0.0, std::sqrt(0.5)}},
                     {"scale", {placementScale, placementScale, placementScale}}});
    return builder;
}

TEST(DensityGridScene, GridIsPlacedByTheNodeThenItsOwnTransform) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "smoke.vdb", smallGrid());
    std::filesystem::path file = boxScene(gridMedium({{"uri", "smoke.vdb"}, {"node", 1}})).writeGltf(directory / "s.gltf");
    LoadedScene loaded = loadScene(file);
    ASSERT_EQ(loaded.scene.densityGrids.size(), 1u);
    ASSERT_EQ(loaded.scene.media.size(), 1u);
    EXPECT_EQ(loaded.scene.media[0].densityGrid, 0);
    const SceneDensityGrid& placed = loaded.scene.densityGrids[0];
    EXPECT_EQ(placed.grid.values, smallGrid().values);
    // Index (1, 0, 0) is local (-0.4, 0.25, 0); the node scales it by 2 to (-0.8, 0.5, 0),
    // turns it a quarter about y to (0, 0.5, 0.8) and moves it to (1, 2.5, 3.8).
    glm::dvec4 world = placed.indexToWorld * glm::dvec4(1.0, 0.0, 0.0, 1.0);
    EXPECT_NEAR(world.x, 1.0, 1e-6);
    EXPECT_NEAR(world.y, 2.5, 1e-6);
    EXPECT_NEAR(world.z, 3.8, 1e-6);
    EXPECT_NE(std::find(loaded.externalFiles.begin(), loaded.externalFiles.end(),
                        std::filesystem::canonical(directory / "smoke.vdb")),
              loaded.externalFiles.end());
}

TEST(DensityGridScene, SceneMediumGridWithoutNodeIsInWorldSpace) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "fog.vdb", smallGrid());
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f))}});
    builder.document()["extensions"]["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", 0.1}, {"density", {{"uri", "fog.vdb"}, {"grid", "density"}}}};
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "fog.gltf"));
    ASSERT_EQ(loaded.scene.densityGrids.size(), 1u);
    EXPECT_EQ(loaded.scene.media[size_t(loaded.scene.sceneMedium)].densityGrid, 0);
    EXPECT_EQ(loaded.scene.densityGrids[0].indexToWorld, smallGrid().indexToLocal);
}

TEST(DensityGridScene, WrittenSceneHasTheGridsCurrentVoxels) {
    TemporaryDirectory directory;
    std::filesystem::create_directories(directory / "in");
    std::filesystem::create_directories(directory / "out");
    writeDensityGridVdb(directory / "in" / "smoke.vdb", smallGrid());
    std::filesystem::path original =
        boxScene(gridMedium({{"uri", "smoke.vdb"}, {"node", 1}})).writeGltf(directory / "in" / "s.gltf");
    LoadedScene loaded = loadScene(original);
    std::vector<float> fitted = smallGrid().values;
    fitted[3] = 7.5f;
    setParameter(loaded.scene, "media/smoke/density", fitted);
    writeSceneWithParameters(original, loaded.scene, directory / "out" / "scene.gltf");
    EXPECT_TRUE(std::filesystem::exists(directory / "out" / "scene.materials0.density.vdb"));
    LoadedScene again = loadScene(directory / "out" / "scene.gltf");
    ASSERT_EQ(again.scene.densityGrids.size(), 1u);
    EXPECT_EQ(again.scene.densityGrids[0].grid.values, fitted);
    EXPECT_EQ(again.scene.densityGrids[0].grid.firstVoxel, smallGrid().firstVoxel);
    EXPECT_EQ(again.scene.densityGrids[0].indexToWorld, loaded.scene.densityGrids[0].indexToWorld);
}

TEST(DensityGridScene, BadReferencesNameTheField) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "smoke.vdb", smallGrid());
    const std::string field = "materials[0].extensions.VKDR_participating_media.density";
    auto write = [&](json density, double placementScale = 2.0) {
        return boxScene(gridMedium(std::move(density)), placementScale).writeGltf(directory / "bad.gltf");
    };
    expectLoadError(write({{"uri", "absent.vdb"}}), {field + ".uri", "absent.vdb"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"grid", "temperature"}}), {field, "temperature", "density"});
    expectLoadError(write({{"grid", "density"}}), {field + ".uri", "missing"});
    expectLoadError(write("smoke.vdb"), {field, "expected an object"});
    expectLoadError(write({{"uri", "data:application/octet-stream;base64,AAAA"}}), {field + ".uri", "data: URI"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 7}}), {field + ".node", "out of range"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", "one"}}), {field + ".node", "node index"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 1}}, 0.0), {field, "singular"});
    expectLoadError(write({{"uri", "../smoke.vdb"}}), {field + ".uri", "outside"});
}

}  // namespace
}  // namespace vkdr::test
