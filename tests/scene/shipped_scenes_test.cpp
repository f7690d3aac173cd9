// Every scene shipped in scenes/ and the example in docs/scene-format.md loads, and
// the Cornell box keeps the properties the renderer and the thesis comparison rely on.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "scene/load_scene.h"
#include "scene/medium_at.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

const std::filesystem::path kScenes = VKDR_TEST_SCENES_DIR;
const std::filesystem::path kData = VKDR_TEST_DATA_DIR;

const Material& materialNamed(const Scene& scene, const std::string& name) {
    for (const Material& material : scene.materials) {
        if (material.name == name) {
            return material;
        }
    }
    throw std::runtime_error("no material " + name);
}

glm::vec3 normalOf(const Scene& scene, size_t t) {
    glm::vec3 p0 = scene.positions[scene.triangles[t].x];
    return glm::normalize(glm::cross(scene.positions[scene.triangles[t].y] - p0,
                                     scene.positions[scene.triangles[t].z] - p0));
}

TEST(ShippedScenes, AllLoadWithoutWarnings) {
    size_t count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
        if (entry.path().extension() == ".gltf" || entry.path().extension() == ".glb") {
            SCOPED_TRACE(entry.path().string());
            LoadedScene loaded = loadScene(entry.path());
            EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
            EXPECT_EQ(loaded.scene.cameras.size(), 1u);
            ++count;
        }
    }
    EXPECT_GE(count, 3u);
}

TEST(ShippedScenes, CornellBoxMatchesThePublishedSetup) {
    Scene scene = loadScene(kScenes / "cornell_box.gltf").scene;
    ASSERT_EQ(scene.cameras.size(), 1u);
    const Camera& camera = scene.cameras[0];
    EXPECT_NEAR(camera.yfov, glm::radians(39.3f), 1e-3f);
    EXPECT_FLOAT_EQ(camera.aspectRatio, 1.0f);
    glm::vec3 position(camera.cameraToWorld[3]);
    EXPECT_NEAR(glm::distance(position, glm::vec3(2.78f, 2.73f, -8.0f)), 0.0f, 1e-5f);
    glm::vec3 forward = -glm::vec3(camera.cameraToWorld[2]);
    EXPECT_NEAR(glm::distance(forward, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    glm::vec3 right(camera.cameraToWorld[0]);
    EXPECT_NEAR(glm::distance(right, glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);  // red wall (x = 5.5) on the left

    const Material& light = materialNamed(scene, "light");
    EXPECT_NEAR(light.emission.r, 17.0f, 1e-4f);
    EXPECT_NEAR(light.emission.g, 0.7059f * 17.0f, 1e-3f);
    EXPECT_NEAR(light.emission.b, 0.2353f * 17.0f, 1e-3f);
    EXPECT_FALSE(light.doubleSided);
    EXPECT_NEAR(materialNamed(scene, "red").baseColor.r, 0.63f, 1e-6f);
    EXPECT_NEAR(materialNamed(scene, "green").baseColor.g, 0.45f, 1e-6f);

    // Triangles in file order: floor, ceiling, back, right and left walls (2 each),
    // the light (2), the short block (10), the tall block (10).
    ASSERT_EQ(scene.triangles.size(), 32u);
    auto centroid = [&](size_t t) {
        glm::uvec3 c = scene.triangles[t];
        return (scene.positions[c.x] + scene.positions[c.y] + scene.positions[c.z]) / 3.0f;
    };
    auto centreOf = [&](size_t first, size_t count) {
        glm::vec3 sum(0.0f);
        for (size_t t = first; t < first + count; ++t) sum += centroid(t);
        return sum / float(count);
    };
    glm::vec3 room = centreOf(0, 10);
    for (size_t t = 0; t < 10; ++t) {
        EXPECT_GT(glm::dot(normalOf(scene, t), room - centroid(t)), 0.0f) << "wall triangle " << t;
    }
    for (size_t t = 10; t < 12; ++t) {
        EXPECT_EQ(scene.triangleMaterial[t], scene.triangleMaterial[10]);
        EXPECT_EQ(scene.materials[scene.triangleMaterial[t]].name, "light");
        EXPECT_GT(-normalOf(scene, t).y, 0.999f) << "the light must face down";
        EXPECT_NEAR(centroid(t).y, 5.487f, 1e-5f);
    }
    for (size_t block : {12u, 22u}) {
        glm::vec3 inside = centreOf(block, 10);
        for (size_t t = block; t < block + 10; ++t) {
            EXPECT_GT(glm::dot(normalOf(scene, t), centroid(t) - inside), 0.0f) << "block triangle " << t;
        }
    }
}

TEST(ShippedScenes, FogAndSmokeMedia) {
    Scene fog = loadScene(kScenes / "cornell_fog.gltf").scene;
    ASSERT_GE(fog.sceneMedium, 0);
    EXPECT_EQ(fog.media[size_t(fog.sceneMedium)].name, "fog");
    EXPECT_EQ(getParameter(fog, "media/fog/sigma_a"), std::vector<float>(3, 0.01f));
    EXPECT_EQ(getParameter(fog, "media/fog/sigma_s"), std::vector<float>(3, 0.04f));
    EXPECT_EQ(mediumAt(fog, glm::vec3(fog.cameras[0].cameraToWorld[3])), fog.sceneMedium);

    Scene smoke = loadScene(kScenes / "cornell_smoke.gltf").scene;
    EXPECT_EQ(smoke.sceneMedium, kNoMedium);
    EXPECT_EQ(getParameter(smoke, "media/smoke/sigma_s"), std::vector<float>(3, 4.0f));
    EXPECT_EQ(getParameter(smoke, "media/smoke/g"), std::vector<float>{0.3f});
    EXPECT_EQ(mediumAt(smoke, glm::vec3(smoke.cameras[0].cameraToWorld[3])), kNoMedium);
    EXPECT_EQ(mediumAt(smoke, {3.685f, 1.0f, 3.515f}), 0);
}

TEST(ShippedScenes, DocumentationExampleLoadsAndIsQuotedVerbatim) {
    LoadedScene loaded = loadScene(kData / "example.gltf");
    EXPECT_TRUE(loaded.warnings.empty());
    EXPECT_GE(loaded.scene.sceneMedium, 0);
    EXPECT_EQ(loaded.scene.cameras.size(), 1u);

    auto read = [](const std::filesystem::path& file) {
        std::stringstream text;
        text << std::ifstream(file).rdbuf();
        return text.str();
    };
    std::string example = read(kData / "example.gltf");
    EXPECT_NE(read(std::filesystem::path(VKDR_DOCS_DIR) / "scene-format.md").find(example), std::string::npos)
        << "docs/scene-format.md must quote tests/scene/data/example.gltf exactly";
}

}  // namespace
}  // namespace vkdr::test
