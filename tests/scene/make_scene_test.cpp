// vkdr-make-scene writes loadable scenes of the requested size.
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/wait.h>

#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

LoadedScene makeAndLoad(const TemporaryDirectory& directory, const std::string& arguments) {
    std::filesystem::path file = directory / "generated.glb";
    std::string command = std::string(VKDR_MAKE_SCENE_PATH) + " " + arguments + " -o " + file.string() +
                          " > /dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return loadScene(file);
}

TEST(MakeScene, ProducesTheRequestedTriangleCount) {
    TemporaryDirectory directory;
    for (size_t requested : {2000u, 30000u}) {
        LoadedScene loaded = makeAndLoad(directory, "--triangles " + std::to_string(requested));
        const Scene& scene = loaded.scene;
        EXPECT_NEAR(double(scene.triangles.size()), double(requested), 0.03 * double(requested));
        EXPECT_TRUE(loaded.warnings.empty());
        EXPECT_EQ(scene.cameras.size(), 1u);
        EXPECT_EQ(scene.sceneMedium, kNoMedium);
        bool hasLight = false;
        for (const Material& material : scene.materials) {
            hasLight = hasLight || material.isEmissive();
        }
        EXPECT_TRUE(hasLight);
    }
}

TEST(MakeScene, AddsTheFogMedium) {
    TemporaryDirectory directory;
    Scene scene = makeAndLoad(directory, "--triangles 5000 --fog 0.02,0.1").scene;
    ASSERT_GE(scene.sceneMedium, 0);
    EXPECT_EQ(scene.media[size_t(scene.sceneMedium)].name, "fog");
    EXPECT_EQ(scene.media[size_t(scene.sceneMedium)].sigma_a, glm::vec3(0.02f));
    EXPECT_EQ(scene.media[size_t(scene.sceneMedium)].sigma_s, glm::vec3(0.1f));
}

// --scale multiplies every length: the bounds of the geometry and the camera position.
TEST(MakeScene, ScalesTheRoomAndTheCamera) {
    TemporaryDirectory directory;
    const Scene unit = makeAndLoad(directory, "--triangles 3000").scene;
    const Scene scaled = makeAndLoad(directory, "--triangles 3000 --scale 40").scene;
    ASSERT_EQ(unit.positions.size(), scaled.positions.size());
    for (size_t i = 0; i < unit.positions.size(); ++i) {
        EXPECT_NEAR(glm::distance(scaled.positions[i], 40.0f * unit.positions[i]), 0.0f, 1e-3f) << i;
    }
    const glm::vec3 unitCamera = unit.cameras[0].cameraToWorld[3];
    const glm::vec3 scaledCamera = scaled.cameras[0].cameraToWorld[3];
    EXPECT_NEAR(glm::distance(scaledCamera, 40.0f * unitCamera), 0.0f, 1e-4f);
    EXPECT_NE(unitCamera, glm::vec3(0.0f));
}

// However few the spheres, the light hangs above all of them (a sphere around it would
// leave the room black) and the camera is outside them.
TEST(MakeScene, SpheresStayBelowTheLightAndAwayFromTheCamera) {
    TemporaryDirectory directory;
    for (size_t requested : {50u, 3000u, 12000u, 30000u}) {
        const Scene scene = makeAndLoad(directory, "--triangles " + std::to_string(requested)).scene;
        const uint32_t spheres = scene.triangleMaterial.back();
        float lightY = 1e9f, sphereTop = -1e9f;
        for (size_t t = 0; t < scene.triangles.size(); ++t) {
            const uint32_t material = scene.triangleMaterial[t];
            for (int c = 0; c < 3; ++c) {
                const float y = scene.positions[scene.triangles[t][c]].y;
                if (scene.materials[material].isEmissive()) {
                    lightY = std::min(lightY, y);
                } else if (material == spheres) {
                    sphereTop = std::max(sphereTop, y);
                }
            }
        }
        EXPECT_LT(sphereTop, lightY) << requested << " triangles";
        const glm::vec3 camera = scene.cameras[0].cameraToWorld[3];
        float nearest = 1e9f;
        for (size_t t = 0; t < scene.triangles.size(); ++t) {
            if (scene.triangleMaterial[t] == spheres) {
                nearest = std::min(nearest, glm::distance(camera, scene.positions[scene.triangles[t].x]));
            }
        }
        EXPECT_GT(nearest, 0.5f) << requested << " triangles";
    }
}

TEST(MakeScene, SpheresFaceOutwards) {
    TemporaryDirectory directory;
    Scene scene = makeAndLoad(directory, "--triangles 3000").scene;
    // This budget makes a single sphere: every one of its triangles faces away from
    // the centre of its bounding box.
    uint32_t spheres = scene.triangleMaterial.back();
    glm::vec3 low(1e9f), high(-1e9f);
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.triangleMaterial[t] == spheres) {
            for (int c = 0; c < 3; ++c) {
                low = glm::min(low, scene.positions[scene.triangles[t][c]]);
                high = glm::max(high, scene.positions[scene.triangles[t][c]]);
            }
        }
    }
    glm::vec3 centre = (low + high) * 0.5f;
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.triangleMaterial[t] != spheres) continue;
        glm::vec3 p0 = scene.positions[scene.triangles[t].x];
        glm::vec3 p1 = scene.positions[scene.triangles[t].y];
        glm::vec3 p2 = scene.positions[scene.triangles[t].z];
        ASSERT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), (p0 + p1 + p2) / 3.0f - centre), 0.0f) << t;
    }
}

TEST(MakeScene, RefusesAnOutputThatIsNotBinaryGltf) {
    TemporaryDirectory directory;
    const std::filesystem::path file = directory / "scene.gltf";
    const std::filesystem::path err = directory / "stderr";
    std::string command = std::string(VKDR_MAKE_SCENE_PATH) + " --triangles 100 -o " + file.string() + " 2> " +
                          err.string();
    int status = std::system(command.c_str());
    EXPECT_EQ(WEXITSTATUS(status), 2);
    EXPECT_FALSE(std::filesystem::exists(file));
    std::ifstream stream(err);
    std::string message((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    EXPECT_EQ(message.rfind("error: -o " + file.string() + ": the scene is written as binary glTF", 0), 0u) << message;
}

}  // namespace
}  // namespace vkdr::test
