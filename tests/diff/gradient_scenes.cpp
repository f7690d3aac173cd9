#include "gradient_scenes.h"

namespace vkdr::test {
namespace {

// A quad in the plane y = `y`, facing -y (down).
TestMesh ceilingLamp(float y, float halfSize, int material) {
    TestMesh m;
    m.material = material;
    m.positions = {{-halfSize, y, -halfSize}, {halfSize, y, -halfSize}, {halfSize, y, halfSize}, {-halfSize, y, halfSize}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

}  // namespace

TestGltf room() {
    TestGltf g;
    g.materials = {diffuseMaterial("walls", glm::vec3(0.6f, 0.5f, 0.4f)),
                   emissiveMaterial("lamp", glm::vec3(6.0f, 5.0f, 4.0f), false)};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), ceilingLamp(0.95f, 0.3f, 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.9f);
    g.yfov = 1.0f;
    return g;
}

TestGltf foggyRoom() {
    TestGltf g = room();
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.1, 0.15, 0.2}}, {"sigma_s", {0.5, 0.4, 0.3}}, {"g", 0.3}};
    return g;
}

TestGltf smokeRoom() {
    TestGltf g = room();
    g.materials.push_back(vkdrMediumMaterial("smoke", glm::vec3(0.2f), glm::vec3(2.0f, 1.5f, 1.0f), 0.5f));
    g.meshes.push_back(box(glm::vec3(-0.4f, -0.9f, -0.2f), glm::vec3(0.4f, -0.1f, 0.6f), 2));
    return g;
}

}  // namespace vkdr::test
