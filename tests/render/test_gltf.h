#pragma once
// Builds small glTF scenes for the render tests: meshes, materials and a camera,
// written as .gltf plus a .bin buffer.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace vkdr::test {

struct TestMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;  // counter-clockwise seen from the front
    int material = 0;
    std::vector<glm::vec3> normals;     // the NORMAL attribute, one per position, or none
    std::vector<glm::vec4> colors;      // the COLOR_0 attribute (RGBA floats), one per position, or none
};

// A node placing KHR_lights_punctual light `light`, shining along `direction`.
struct TestLightNode {
    int light = 0;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
};

// Axis-aligned box, normals pointing out.
TestMesh box(glm::vec3 lo, glm::vec3 hi, int material);
// Icosphere (`subdivisions` times split), normals pointing out.
TestMesh sphere(glm::vec3 centre, float radius, int subdivisions, int material);
// Rectangle [lo, hi] in the plane z = `z`, facing +z when `facingPlusZ`.
TestMesh rectangleZ(glm::vec2 lo, glm::vec2 hi, float z, bool facingPlusZ, int material);
// Square in the plane z = `z`, centred on (cx, cy), facing +z when `facingPlusZ`.
TestMesh quadZ(float cx, float cy, float halfSize, float z, bool facingPlusZ, int material);

// A further camera node (the scene's camera definition), named, at `position` looking at
// `target` with +Y up.
struct TestCameraNode {
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
};

struct TestGltf {
    std::vector<TestMesh> meshes;
    nlohmann::json materials = nlohmann::json::array();
    nlohmann::json extensions = nlohmann::json::object();  // root extensions
    nlohmann::json lights = nlohmann::json::array();       // KHR_lights_punctual's definitions
    std::vector<TestLightNode> lightNodes;
    std::vector<TestCameraNode> moreCameras;  // after the first camera
    glm::vec3 cameraPosition{0.0f};
    bool cameraLooksAlongPlusZ = true;  // else along -Z
    float yfov = 0.5f;
    float aspectRatio = 1.0f;
    float orthographicHalfHeight = 0.0f;  // > 0: the cameras are orthographic, of this ymag

    // Writes `<dir>/<name>.gltf` and its buffer; returns the .gltf path.
    std::filesystem::path write(const std::filesystem::path& dir, const std::string& name) const;
};

nlohmann::json emissiveMaterial(const std::string& name, glm::vec3 radiance, bool doubleSided);
nlohmann::json diffuseMaterial(const std::string& name, glm::vec3 albedo);
// The medium spelled with our own extension.
nlohmann::json vkdrMediumMaterial(const std::string& name, glm::vec3 sigma_a, glm::vec3 sigma_s, float g);
// The medium spelled as Blender writes it: transmission 1, IOR 1, KHR_materials_volume.
nlohmann::json khrVolumeMaterial(const std::string& name, glm::vec3 attenuationColor, float attenuationDistance);

}  // namespace vkdr::test
