// Medium boundaries: closedness, outward winding, the medium outside each boundary,
// and mediumAt.
#include <gtest/gtest.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/medium_at.h"
#include "scene/scene_warnings.h"

namespace vkdr::test {
namespace {

json mediumMaterial(const std::string& name, float sigma_s) {
    return {{"name", name}, {"extensions", {{"VKDR_participating_media", {{"sigma_s", sigma_s}}}}}};
}

int32_t mediumNamed(const Scene& scene, const std::string& name) {
    for (size_t m = 0; m < scene.media.size(); ++m) {
        if (scene.media[m].name == name) {
            return int32_t(m);
        }
    }
    ADD_FAILURE() << "no medium " << name;
    return kNoMedium;
}

// A box whose faces do not share vertices, as exporters write meshes with UV seams.
MeshData boxWithSplitFaces(glm::vec3 min, glm::vec3 max) {
    MeshData shared = box(min, max);
    MeshData split;
    for (size_t i = 0; i < shared.indices.size(); ++i) {
        split.positions.push_back(shared.positions[shared.indices[i]]);
    }
    return split;
}

// Two meshes as one: the second's vertices follow the first's.
MeshData joined(const MeshData& first, const MeshData& second) {
    MeshData both = first;
    both.positions.insert(both.positions.end(), second.positions.begin(), second.positions.end());
    for (uint32_t index : second.indices) both.indices.push_back(index + uint32_t(first.positions.size()));
    return both;
}

// A scene of one mesh of the medium "smoke".
Scene smokeMesh(const std::filesystem::path& file, const MeshData& mesh) {
    GltfBuilder builder;
    int smoke = builder.addMaterial(mediumMaterial("smoke", 1.0f));
    builder.addNode({{"mesh", builder.addMesh("smoke", mesh, smoke)}});
    return loadScene(builder.writeGltf(file)).scene;
}

// A scene of one box of the medium "smoke" from the origin to `corner`, in vacuum.
Scene smokeBox(const std::filesystem::path& directory, glm::vec3 corner) {
    return smokeMesh(directory / "box.gltf", box({0, 0, 0}, corner));
}

TEST(MediumBoundaries, FlipsInwardWoundBoundariesAndWeldsSplitVertices) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int smoke = builder.addMaterial(mediumMaterial("smoke", 1.0f));
    builder.addNode({{"mesh", builder.addMesh("inward", box({0, 0, 0}, {2, 2, 2}, true), smoke)}});
    builder.addNode({{"mesh", builder.addMesh("split", boxWithSplitFaces({5, 0, 0}, {6, 1, 1}), smoke)}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "winding.gltf"));
    const Scene& scene = loaded.scene;

    ASSERT_EQ(scene.triangles.size(), 24u);
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        glm::vec3 p0 = scene.positions[scene.triangles[t].x];
        glm::vec3 p1 = scene.positions[scene.triangles[t].y];
        glm::vec3 p2 = scene.positions[scene.triangles[t].z];
        glm::vec3 centre = t < 12 ? glm::vec3(1.0f) : glm::vec3(5.5f, 0.5f, 0.5f);
        glm::vec3 outward = (p0 + p1 + p2) / 3.0f - centre;
        EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), outward), 0.0f) << "triangle " << t;
    }
    EXPECT_TRUE(loaded.warnings.empty());
}

// Each closed surface of one boundary is wound by its own volume: a box wound inwards
// beside one wound outwards, in one mesh, loads as both wound outwards.
TEST(MediumBoundaries, WindsEachShellOfABoundaryOnItsOwn) {
    TemporaryDirectory directory;
    const MeshData big = box({0, 0, 0}, {2, 2, 2});
    const Scene outwards = smokeMesh(directory / "outwards.gltf", joined(big, box({3, 0, 0}, {4, 1, 1})));
    const Scene mixed = smokeMesh(directory / "mixed.gltf", joined(big, box({3, 0, 0}, {4, 1, 1}, true)));
    EXPECT_EQ(mixed.triangles, outwards.triangles);
    EXPECT_EQ(mixed.triangleOutsideMedium, outwards.triangleOutsideMedium);
    EXPECT_EQ(mediumAt(mixed, {3.5f, 0.5f, 0.5f}), 0);
    EXPECT_EQ(mediumAt(mixed, {1, 1, 1}), 0);
    EXPECT_EQ(mediumAt(mixed, {2.5f, 0.5f, 0.5f}), kNoMedium);
}

// A shell inside another bounds a cavity, wound inwards however the file winds the pair;
// a pair wound the same way is refused, since which was meant is a guess.
TEST(MediumBoundaries, AShellInsideAnotherBoundsACavity) {
    TemporaryDirectory directory;
    const glm::vec3 outerMin(0.0f), outerMax(4.0f), innerMin(1.0f), innerMax(3.0f);
    const Scene hollow =
        smokeMesh(directory / "hollow.gltf", joined(box(outerMin, outerMax), box(innerMin, innerMax, true)));
    const Scene insideOut =
        smokeMesh(directory / "inside_out.gltf", joined(box(outerMin, outerMax, true), box(innerMin, innerMax)));
    EXPECT_EQ(insideOut.triangles, hollow.triangles);
    for (const Scene* scene : {&hollow, &insideOut}) {
        EXPECT_EQ(mediumAt(*scene, {2, 2, 2}), kNoMedium);
        EXPECT_EQ(mediumAt(*scene, {0.5f, 0.5f, 0.5f}), 0);
        EXPECT_EQ(mediumAt(*scene, {5, 5, 5}), kNoMedium);
    }
    for (bool inward : {false, true}) {
        GltfBuilder builder;
        int smoke = builder.addMaterial(mediumMaterial("smoke", 1.0f));
        MeshData sameWay = joined(box(outerMin, outerMax, inward), box(innerMin, innerMax, inward));
        builder.addNode({{"mesh", builder.addMesh("nested", sameWay, smoke)}});
        expectLoadError(builder.writeGltf(directory / "same_way.gltf"),
                        {"meshes[0] ('nested') at nodes[0]", "medium 'smoke'",
                         "a closed surface of it lies inside another and is wound the same way"});
    }
}

// A regular octahedron of vertices at `radius` on the axes, wound outwards.
MeshData octahedron(float radius) {
    MeshData mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {radius, -radius}) {
            glm::vec3 vertex(0.0f);
            vertex[axis] = sign;
            mesh.positions.push_back(vertex);  // +x, -x, +y, -y, +z, -z
        }
    }
    for (int octant = 0; octant < 8; ++octant) {
        const uint32_t x = octant & 1, y = 2 + (octant >> 1 & 1), z = 4 + (octant >> 2 & 1);
        const bool odd = ((octant & 1) + (octant >> 1 & 1) + (octant >> 2 & 1)) % 2 == 1;
        mesh.indices.insert(mesh.indices.end(), {x, odd ? z : y, odd ? y : z});
    }
    return mesh;
}

// Shells wound alike that intersect (a cloud of shapes joined into one mesh) are not
// nested: the mesh loads, with a warning, whichever of them comes first, whether or
// not one's box lies within the other's, and whichever of their triangles lie inside
// the other.
TEST(MediumBoundaries, ShellsThatIntersectAreWarnedOfNotRefused) {
    TemporaryDirectory directory;
    const MeshData diamond = octahedron(2.0f);
    // Each box's box lies within the octahedron's. The first pokes out of its faces with
    // some triangles' centres inside it; all of the second's triangles' centres lie
    // outside it, and the centre of one of its triangles inside the box.
    const MeshData pokingCube = box({0.3f, 0.3f, 0.3f}, {1.2f, 1.2f, 1.2f});
    const MeshData coveringCube = box({0.3f, 0.3f, 0.3f}, {1.6f, 1.6f, 1.6f});
    // Boxes side by side, overlapping: neither's box lies within the other's.
    const MeshData left = box({-1.0f, -1.0f, -1.0f}, {0.5f, 1.0f, 1.0f});
    const MeshData right = box({0.0f, -1.0f, -1.0f}, {1.5f, 1.0f, 1.0f});
    for (const MeshData& mesh : {joined(diamond, pokingCube), joined(pokingCube, diamond),
                                 joined(diamond, coveringCube), joined(coveringCube, diamond), joined(left, right),
                                 joined(right, left)}) {
        GltfBuilder builder;
        int smoke = builder.addMaterial(mediumMaterial("smoke", 1.0f));
        builder.addNode({{"mesh", builder.addMesh("cloud", mesh, smoke)}});
        LoadedScene loaded = loadScene(builder.writeGltf(directory / "cloud.gltf"));
        ASSERT_EQ(loaded.warnings.size(), 1u);
        EXPECT_NE(loaded.warnings[0].find("two closed surfaces of it intersect"), std::string::npos)
            << loaded.warnings[0];
        EXPECT_EQ(mediumAt(loaded.scene, {0.1f, 0.1f, 0.1f}), 0);
    }
}

TEST(MediumBoundaries, NestedBoundariesSitInTheInnermostEnclosingMedium) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int outer = builder.addMaterial(mediumMaterial("outer", 1.0f));
    int inner = builder.addMaterial(mediumMaterial("inner", 2.0f));
    int side = builder.addMaterial(mediumMaterial("side", 3.0f));
    int wall = builder.addMaterial({{"name", "wall"}});
    builder.addNode({{"mesh", builder.addMesh("inner", box({2, 2, 2}, {4, 4, 4}), inner)}});
    builder.addNode({{"mesh", builder.addMesh("outer", box({0, 0, 0}, {10, 10, 10}), outer)}});
    builder.addNode({{"mesh", builder.addMesh("side", box({6, 6, 6}, {8, 8, 8}, true), side)}});
    builder.addNode({{"mesh", builder.addMesh("floor", floorQuad(20.0f, -1.0f), wall)}});
    builder.document()["extensions"]["VKDR_participating_media"] = {{"name", "fog"}, {"sigma_s", 0.1}};
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "nested.gltf"));
    const Scene& scene = loaded.scene;
    EXPECT_TRUE(loaded.warnings.empty());

    int32_t fog = mediumNamed(scene, "fog");
    int32_t outerMedium = mediumNamed(scene, "outer");
    EXPECT_EQ(scene.sceneMedium, fog);
    ASSERT_EQ(scene.triangleOutsideMedium.size(), 38u);
    for (size_t t = 0; t < 12; ++t) {
        EXPECT_EQ(scene.triangleOutsideMedium[t], outerMedium) << "inner box, triangle " << t;
        EXPECT_EQ(scene.triangleOutsideMedium[t + 12], fog) << "outer box, triangle " << t;
        EXPECT_EQ(scene.triangleOutsideMedium[t + 24], outerMedium) << "side box, triangle " << t;
    }
    EXPECT_EQ(scene.triangleOutsideMedium[36], kNoMedium);  // the floor is no boundary

    EXPECT_EQ(mediumAt(scene, {3, 3, 3}), mediumNamed(scene, "inner"));
    EXPECT_EQ(mediumAt(scene, {7, 7, 7}), mediumNamed(scene, "side"));
    EXPECT_EQ(mediumAt(scene, {5, 1, 5}), outerMedium);
    EXPECT_EQ(mediumAt(scene, {1, 9, 9}), outerMedium);
    EXPECT_EQ(mediumAt(scene, {-5, 5, 5}), fog);
    EXPECT_EQ(mediumAt(scene, {20, 20, 20}), fog);
}

// A camera on a boundary's face (or on its edge, between two triangles) is warned of,
// naming it and the medium; one off the face by more than float's reach is not, nor one
// inside. (The scene has no light, which is warned of too.)
TEST(MediumBoundaries, WarnsOfACameraOnABoundary) {
    TemporaryDirectory directory;
    Scene scene = smokeBox(directory.path(), {2, 2, 2});
    scene.cameras = {Camera{.name = "face"}, Camera{.name = "edge"}, Camera{.name = "off"}, Camera{.name = "inside"}};
    scene.cameras[0].cameraToWorld[3] = glm::vec4(0.5f, 1.5f, 2.0f, 1.0f);
    scene.cameras[1].cameraToWorld[3] = glm::vec4(2.0f, 1.0f, 2.0f, 1.0f);
    scene.cameras[2].cameraToWorld[3] = glm::vec4(0.5f, 1.5f, 2.001f, 1.0f);
    scene.cameras[3].cameraToWorld[3] = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
    std::vector<std::string> warnings;
    for (const std::string& warning : sceneWarnings(scene, "smoke.gltf")) {
        if (warning.find("lies on the boundary") != std::string::npos) warnings.push_back(warning);
    }
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_NE(warnings[0].find("camera 'face' lies on the boundary of medium 'smoke'"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[1].find("camera 'edge' lies on the boundary of medium 'smoke'"), std::string::npos)
        << warnings[1];
}

TEST(MediumBoundaries, VacuumOutsideWithoutSceneMedium) {
    TemporaryDirectory directory;
    Scene scene = smokeBox(directory.path(), {1, 1, 1});
    EXPECT_EQ(mediumAt(scene, {0.5f, 0.5f, 0.5f}), 0);
    EXPECT_EQ(mediumAt(scene, {2, 2, 2}), kNoMedium);
    EXPECT_EQ(scene.triangleOutsideMedium, std::vector<int32_t>(12, kNoMedium));
}

TEST(MediumBoundaries, WarnsAboutOverlappingMedia) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int a = builder.addMaterial(mediumMaterial("a", 1.0f));
    int b = builder.addMaterial(mediumMaterial("b", 1.0f));
    builder.addNode({{"mesh", builder.addMesh("a", box({0, 0, 0}, {2, 2, 2}), a)}});
    builder.addNode({{"mesh", builder.addMesh("b", box({1, 1, 1}, {3, 3, 3}), b)}});
    LoadedScene loaded = loadScene(builder.writeGltf(directory / "overlap.gltf"));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("overlapping media are not supported"), std::string::npos);
}

TEST(MediumBoundaries, RejectsInconsistentlyWoundBoundaries) {
    TemporaryDirectory directory;
    GltfBuilder builder;
    int smoke = builder.addMaterial(mediumMaterial("smoke", 1.0f));
    MeshData twisted = box({0, 0, 0}, {1, 1, 1});
    std::swap(twisted.indices[1], twisted.indices[2]);
    builder.addNode({{"mesh", builder.addMesh("twisted", twisted, smoke)}});
    EXPECT_THROW(loadScene(builder.writeGltf(directory / "twisted.gltf")), Error);
}

}  // namespace
}  // namespace vkdr::test
