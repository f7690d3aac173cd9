// Density, emission and albedo grids referenced from glTF: placement by the grid's own
// transform and a node's, on materials and the scene medium; the grid files among the
// files read, and the fitted voxels in the grid a written scene refers to; and one error
// naming the field for each kind of bad reference.
#include <gtest/gtest.h>

#include <cmath>

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/IO.h>

#include "../image/scratch_directory.h"
#include "core/error.h"
#include "expect_error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"
#include "scene/scene_warnings.h"
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
// gridMedium of smoke.vdb with one more grid reference under `key` (emissionGrid, albedoGrid).
json smokeMediumWith(const char* key, json reference) {
    json medium = gridMedium({{"uri", "smoke.vdb"}});
    medium["extensions"]["VKDR_participating_media"][key] = std::move(reference);
    return medium;
}

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

// A NanoVDB grid may have voxels too small for OpenVDB's transforms; it renders, but a
// fitted scene could not write it back as .vdb: a run is refused before it starts, and
// writing the scene before any file is written.
TEST(DensityGridScene, AGridTheWrittenSceneCouldNotHoldIsRefusedBeforeAnyWork) {
    TemporaryDirectory directory;
    const std::filesystem::path grid = directory / "smoke.nvdb";
    writeDensityGridNanoVdb(grid, smallGrid());
    nanovdb::GridHandle<> handle = nanovdb::io::readGrid(grid.string());
    handle.grid<float>()->data()->mMap.set(1e-6, nanovdb::Vec3d(0.0), 1.0);
    nanovdb::updateChecksum(*handle.grid<float>());
    nanovdb::io::writeGrid(grid.string(), handle);
    std::filesystem::path original =
        boxScene(gridMedium({{"uri", "smoke.nvdb"}, {"node", 1}})).writeGltf(directory / "s.gltf");
    LoadedScene loaded = loadScene(original);
    const std::vector<std::string> expected = {"smoke.nvdb: grid 'density'", "voxels are too small for OpenVDB",
                                               "cannot be written beside a fitted scene.gltf"};
    expectErrorMentioning([&] { requireWritableDensityGrids(loaded.scene); }, expected);
    expectErrorMentioning([&] { writeSceneWithParameters(original, loaded.scene, directory / "out.gltf"); }, expected);
    EXPECT_FALSE(std::filesystem::exists(directory / "out.gltf"));
    EXPECT_FALSE(std::filesystem::exists(directory / "out.materials0.density.vdb"));
}

// A grid the written scene would put where the scene reads one is refused before any
// file is written: the loaded scene would read the fitted voxels from then on.
TEST(DensityGridScene, WritingOverAGridTheSceneReadsIsRefused) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "scene.materials0.density.vdb", smallGrid());
    std::filesystem::path original = boxScene(gridMedium({{"uri", "scene.materials0.density.vdb"}, {"node", 1}}))
                                         .writeGltf(directory / "original.gltf");
    LoadedScene loaded = loadScene(original);
    const std::string before = readBytes(directory / "scene.materials0.density.vdb");
    std::vector<float> fitted = smallGrid().values;
    fitted[3] = 7.5f;
    setParameter(loaded.scene, "media/smoke/density", fitted);
    expectErrorMentioning([&] { writeSceneWithParameters(original, loaded.scene, directory / "scene.gltf"); },
                          {"scene.materials0.density.vdb", "which the scene reads"});
    EXPECT_EQ(readBytes(directory / "scene.materials0.density.vdb"), before);
    EXPECT_FALSE(std::filesystem::exists(directory / "scene.gltf"));
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
    expectLoadError(write({{"uri", ""}}), {field + ".uri", "empty: give the grid file's path relative to the scene file"});
    expectLoadError(write({{"uri", "data:application/octet-stream;base64,AAAA"}}), {field + ".uri", "data: URI"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 7}}), {field + ".node", "out of range"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", "one"}}), {field + ".node", "expected an index"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 2147483648ll}}), {field + ".node", "2147483648"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 1}}, 0.0), {field, "singular"});
    // A placement that shears the voxels to within 1e-6 of a plane: the rule for a grid file's own transform.
    GltfBuilder sheared = boxScene(gridMedium({{"uri", "smoke.vdb"}, {"node", 1}}));
    sheared.document()["nodes"][1] = {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 1e-9, 0, 0, 0, 0, 1}}};
    expectLoadError(sheared.writeGltf(directory / "sheared.gltf"), {field, "placement", "singular"});
    // The placement node is a root of the scene and a child of the box's node: two places.
    GltfBuilder twice = boxScene(gridMedium({{"uri", "smoke.vdb"}, {"node", 1}}));
    twice.document()["nodes"][0]["children"] = {1};
    expectLoadError(twice.writeGltf(directory / "twice.gltf"), {field, "node 1 has several parents"});
    expectLoadError(write({{"uri", "../smoke.vdb"}}), {field + ".uri", "outside"});
    expectLoadError(write({{"uri", "file:///smoke.vdb"}}), {field + ".uri", "(file:) are not read", "relative"});
    // A data URI in capitals is no data URI to the reader; the message quotes only its start.
    expectLoadError(write({{"uri", "DATA:" + std::string(1000, 'A')}}), {"(DATA:) are not read", "(1005 characters)"});
    // Voxels so small that world-to-index coordinates leave float's range.
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 1}}, 1e-40), {field, "placement", "beyond float's range"});
    // Voxels of 1e20 placed at a scale of 1e20: index-to-world entries beyond float's range.
    DensityGrid vast = smallGrid();
    vast.indexToLocal = glm::dmat4(1e20);
    vast.indexToLocal[3][3] = 1.0;
    writeDensityGridVdb(directory / "smoke.vdb", vast);
    expectLoadError(write({{"uri", "smoke.vdb"}, {"node", 1}}, 1e20), {field, "placement", "1e+40", "too large"});
}

// An emission grid: its own entry among the grids, white emission unless given, its own
// parameter, written back beside the scene with its fitted voxels; a scene medium that
// attenuates nothing may emit through it; bad references name its field.
DensityGrid flameGrid() {
    DensityGrid grid = smallGrid();
    grid.name = "flame";
    grid.values = {1.0f, 0.0f, 0.5f, 2.0f, 0.0f, 4.0f};
    return grid;
}

TEST(DensityGridScene, EmissionGridMultipliesTheEmissionAndIsWrittenBack) {
    TemporaryDirectory directory;
    std::filesystem::create_directories(directory / "in");
    std::filesystem::create_directories(directory / "out");
    writeDensityGridVdb(directory / "in" / "smoke.vdb", smallGrid());
    writeDensityGridVdb(directory / "in" / "fire.vdb", flameGrid());
    std::filesystem::path original =
        boxScene(smokeMediumWith("emissionGrid", {{"uri", "fire.vdb"}, {"node", 1}})).writeGltf(directory / "in" / "s.gltf");
    LoadedScene loaded = loadScene(original);
    ASSERT_EQ(loaded.scene.densityGrids.size(), 2u);
    const Medium& smoke = loaded.scene.media[0];
    EXPECT_EQ(smoke.densityGrid, 0);
    EXPECT_EQ(smoke.emissionGrid, 1);
    EXPECT_EQ(smoke.emission, glm::vec3(1.0f)) << "an emission grid without an emission emits white";
    EXPECT_EQ(loaded.scene.densityGrids[1].grid.values, flameGrid().values);
    EXPECT_NE(loaded.scene.densityGrids[1].indexToWorld, loaded.scene.densityGrids[0].indexToWorld)
        << "only the emission grid is placed by the node";
    const std::vector<std::string> names = parameterNames(loaded.scene);
    EXPECT_NE(std::find(names.begin(), names.end(), "media/smoke/emission_grid"), names.end());
    EXPECT_EQ(getParameter(loaded.scene, "media/smoke/emission_grid"), flameGrid().values);

    std::vector<float> fitted = flameGrid().values;
    fitted[4] = 6.25f;
    setParameter(loaded.scene, "media/smoke/emission_grid", fitted);
    setParameter(loaded.scene, "media/smoke/emission", std::vector<float>{0.0f});
    writeSceneWithParameters(original, loaded.scene, directory / "out" / "scene.gltf");
    EXPECT_TRUE(std::filesystem::exists(directory / "out" / "scene.materials0.emission_grid.vdb"));
    LoadedScene again = loadScene(directory / "out" / "scene.gltf");
    ASSERT_EQ(again.scene.densityGrids.size(), 2u);
    EXPECT_EQ(again.scene.densityGrids[size_t(again.scene.media[0].emissionGrid)].grid.values, fitted);
    EXPECT_EQ(again.scene.densityGrids[size_t(again.scene.media[0].emissionGrid)].grid.name, "flame");
    EXPECT_EQ(again.scene.densityGrids[size_t(again.scene.media[0].emissionGrid)].indexToWorld,
              loaded.scene.densityGrids[1].indexToWorld);
    EXPECT_EQ(again.scene.media[0].emission, glm::vec3(0.0f)) << "an emission fitted to 0 must not read back as white";
}

TEST(DensityGridScene, ASceneMediumClearInAChannelMayEmitThroughAnEmissionGrid) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "fire.vdb", flameGrid());
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(1.0f))}});
    builder.document()["extensions"]["VKDR_participating_media"] = {
        {"name", "air"}, {"emission", {2.0, 1.0, 0.5}}, {"emissionGrid", {{"uri", "fire.vdb"}}}};
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "air.gltf"));
    const Medium& air = loaded.scene.media[size_t(loaded.scene.sceneMedium)];
    EXPECT_FALSE(air.isHeterogeneous());
    EXPECT_EQ(air.emissionGrid, 0);
    builder.document()["extensions"]["VKDR_participating_media"].erase("emissionGrid");
    expectLoadError(builder.writeGltf(directory / "air.gltf"), {"emission[0]", "infinitely bright"});
}

// A grid of no active voxels loads (it is 0 everywhere), with a warning that names the
// medium, the grid's role and its file; grids with voxels give none.
TEST(DensityGridScene, AGridOfNoActiveVoxelsIsWarnedOf) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "smoke.vdb", smallGrid());
    DensityGrid empty;
    empty.name = "flame";
    writeDensityGridVdb(directory / "unfinished.vdb", empty);
    const std::filesystem::path withVoxels =
        boxScene(smokeMediumWith("emissionGrid", {{"uri", "smoke.vdb"}, {"grid", "density"}})).writeGltf(directory / "full.gltf");
    EXPECT_TRUE(sceneWarnings(loadScene(withVoxels).scene, withVoxels).empty());
    const std::filesystem::path file =
        boxScene(smokeMediumWith("emissionGrid", {{"uri", "unfinished.vdb"}, {"grid", "flame"}}))
            .writeGltf(directory / "s.gltf");
    LoadedScene loaded = loadScene(file);
    EXPECT_EQ(loaded.scene.densityGrids.at(size_t(loaded.scene.media[0].emissionGrid)).grid.voxelCount(), 0u);
    const std::vector<std::string> warnings = sceneWarnings(loaded.scene, file);
    ASSERT_EQ(warnings.size(), 1u);
    for (const char* part : {"s.gltf: medium 'smoke'", "emission grid 'flame' in unfinished.vdb",
                             "no active voxels", "emits nothing"}) {
        EXPECT_NE(warnings[0].find(part), std::string::npos) << warnings[0] << " lacks " << part;
    }
}

DensityGrid colourGrid() {
    DensityGrid grid = smallGrid();
    grid.name = "color";
    grid.channels = 3;
    grid.values = {0.1f, 0.2f, 0.3f, 1.0f, 0.0f, 0.5f, 0.25f, 0.75f, 1.0f,
                   0.0f, 0.0f, 0.0f, 0.5f, 0.5f, 0.5f, 0.9f, 0.8f, 0.7f};
    return grid;
}

// An albedo grid: RGB from a vector grid (OpenVDB or NanoVDB), grey from a scalar one;
// its own parameter of 3 values per voxel, written back beside the scene.
TEST(DensityGridScene, AlbedoGridIsReadAsRgbOrGreyAndWrittenBack) {
    TemporaryDirectory directory;
    std::filesystem::create_directories(directory / "in");
    std::filesystem::create_directories(directory / "out");
    writeDensityGridVdb(directory / "in" / "smoke.vdb", smallGrid());
    writeDensityGridNanoVdb(directory / "in" / "colour.nvdb", colourGrid());
    std::filesystem::path original =
        boxScene(smokeMediumWith("albedoGrid", {{"uri", "colour.nvdb"}})).writeGltf(directory / "in" / "s.gltf");
    LoadedScene loaded = loadScene(original);
    ASSERT_EQ(loaded.scene.media[0].albedoGrid, 1);
    const DensityGrid& albedo = loaded.scene.densityGrids[1].grid;
    EXPECT_EQ(albedo.channels, 3);
    EXPECT_EQ(albedo.values, colourGrid().values);
    EXPECT_EQ(getParameter(loaded.scene, "media/smoke/albedo_grid"), colourGrid().values);
    expectErrorMentioning([&] { setParameter(loaded.scene, "media/smoke/albedo_grid", std::vector<float>{1.5f}); },
                          {"media/smoke/albedo_grid", "must be in [0, 1]"});

    std::vector<float> fitted = colourGrid().values;
    fitted[4] = 0.625f;
    setParameter(loaded.scene, "media/smoke/albedo_grid", fitted);
    writeSceneWithParameters(original, loaded.scene, directory / "out" / "scene.gltf");
    EXPECT_TRUE(std::filesystem::exists(directory / "out" / "scene.materials0.albedo_grid.vdb"));
    LoadedScene again = loadScene(directory / "out" / "scene.gltf");
    EXPECT_EQ(again.scene.densityGrids[size_t(again.scene.media[0].albedoGrid)].grid.values, fitted);
    EXPECT_EQ(again.scene.densityGrids[size_t(again.scene.media[0].albedoGrid)].grid.name, "color");

    DensityGrid grey = smallGrid();
    grey.values = {0.0f, 0.5f, 1.0f, 0.25f, 0.75f, 0.125f};
    writeDensityGridVdb(directory / "in" / "grey.vdb", grey);
    LoadedScene greyScene = loadScene(boxScene(smokeMediumWith("albedoGrid", {{"uri", "grey.vdb"}, {"grid", "density"}}))
                                          .writeGltf(directory / "in" / "grey.gltf"));
    const DensityGrid& greyAlbedo = greyScene.scene.densityGrids[1].grid;
    ASSERT_EQ(greyAlbedo.values.size(), 18u);
    for (size_t i = 0; i < grey.values.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(greyAlbedo.values[3 * i + size_t(c)], grey.values[i]);
    }
}

TEST(DensityGridScene, BadAlbedoGridsNameTheFieldAndTheVoxel) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "smoke.vdb", smallGrid());
    writeDensityGridVdb(directory / "colour.vdb", colourGrid());
    const std::string field = "materials[0].extensions.VKDR_participating_media";
    auto write = [&](json grid, const char* key) {
        return boxScene(smokeMediumWith(key, std::move(grid))).writeGltf(directory / "bad.gltf");
    };
    // smallGrid holds 2 and 3: not albedos.
    expectLoadError(write({{"uri", "smoke.vdb"}, {"grid", "density"}}, "albedoGrid"),
                    {field + ".albedoGrid", "voxel", "an albedo must be in [0, 1]"});
    expectLoadError(write({{"uri", "smoke.vdb"}}, "albedoGrid"), {field + ".albedoGrid", "color", "density"});
    // The value shows with the digits that tell it from 1.
    DensityGrid justAbove = smallGrid();
    justAbove.values = {0.0f, 1.0f, std::nextafter(1.0f, 2.0f), 0.5f, 0.25f, 1.0f};
    writeDensityGridVdb(directory / "above.vdb", justAbove);
    expectLoadError(write({{"uri", "above.vdb"}, {"grid", "density"}}, "albedoGrid"),
                    {field + ".albedoGrid", "holds 1.00000012; an albedo must be in [0, 1]"});
    // A vector grid is no emission strength, and the message says what grid it was read as.
    expectLoadError(write({{"uri", "colour.vdb"}, {"grid", "color"}}, "emissionGrid"),
                    {field + ".emissionGrid", "vec3s", "cannot read emission grid 'color'",
                     "not scalar emission strengths"});
}

TEST(DensityGridScene, BadEmissionGridReferencesNameTheField) {
    TemporaryDirectory directory;
    writeDensityGridVdb(directory / "smoke.vdb", smallGrid());
    const std::string field = "materials[0].extensions.VKDR_participating_media.emissionGrid";
    auto write = [&](json grid) {
        return boxScene(smokeMediumWith("emissionGrid", std::move(grid))).writeGltf(directory / "bad.gltf");
    };
    expectLoadError(write({{"uri", "absent.vdb"}}), {field + ".uri", "absent.vdb"});
    expectLoadError(write({{"uri", "smoke.vdb"}}), {field, "flame", "density"});
    expectLoadError(write({{"uri", "smoke.vdb"}, {"grid", "density"}, {"node", 7}}), {field + ".node", "out of range"});
    expectLoadError(write(2.0), {field, "expected an object"});
}

}  // namespace
}  // namespace vkdr::test
