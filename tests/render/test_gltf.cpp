#include "test_gltf.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/quaternion.hpp>

namespace vkdr::test {
namespace {

nlohmann::json vec(glm::vec3 v) {
    return {v.x, v.y, v.z};
}

void appendQuad(TestMesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    uint32_t base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
}

}  // namespace

TestMesh box(glm::vec3 lo, glm::vec3 hi, int material) {
    TestMesh m;
    m.material = material;
    glm::vec3 p[8];
    for (int i = 0; i < 8; ++i) {
        p[i] = glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    }
    appendQuad(m, p[0], p[2], p[3], p[1]);  // z = lo, facing -z
    appendQuad(m, p[4], p[5], p[7], p[6]);  // z = hi, facing +z
    appendQuad(m, p[0], p[1], p[5], p[4]);  // y = lo, facing -y
    appendQuad(m, p[2], p[6], p[7], p[3]);  // y = hi, facing +y
    appendQuad(m, p[0], p[4], p[6], p[2]);  // x = lo, facing -x
    appendQuad(m, p[1], p[3], p[7], p[5]);  // x = hi, facing +x
    return m;
}

TestMesh sphere(glm::vec3 centre, float radius, int subdivisions, int material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : v) {
        p = glm::normalize(p);
    }
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) {
                return it->second;
            }
            v.push_back(glm::normalize(v[a] + v[b]));
            return midpoints[key] = static_cast<uint32_t>(v.size() - 1);
        };
        std::vector<glm::uvec3> next;
        for (const glm::uvec3& tri : f) {
            uint32_t a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
            next.insert(next.end(), {{tri.x, a, c}, {tri.y, b, a}, {tri.z, c, b}, {a, b, c}});
        }
        f = next;
    }
    TestMesh m;
    m.material = material;
    for (const glm::vec3& p : v) {
        m.positions.push_back(centre + radius * p);
    }
    m.triangles = f;
    return m;
}

TestMesh rectangleZ(glm::vec2 lo, glm::vec2 hi, float z, bool facingPlusZ, int material) {
    TestMesh m;
    m.material = material;
    glm::vec3 a(lo.x, lo.y, z), b(hi.x, lo.y, z), c(hi.x, hi.y, z), d(lo.x, hi.y, z);
    if (facingPlusZ) {
        appendQuad(m, a, b, c, d);
    } else {
        appendQuad(m, a, d, c, b);
    }
    return m;
}

TestMesh quadZ(float cx, float cy, float halfSize, float z, bool facingPlusZ, int material) {
    return rectangleZ(glm::vec2(cx - halfSize, cy - halfSize), glm::vec2(cx + halfSize, cy + halfSize), z,
                      facingPlusZ, material);
}

std::filesystem::path TestGltf::write(const std::filesystem::path& dir, const std::string& name) const {
    std::filesystem::create_directories(dir);
    std::vector<unsigned char> bin;
    auto append = [&bin](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), p, p + bytes);
    };
    nlohmann::json gltf;
    gltf["asset"] = {{"version", "2.0"}};
    gltf["scene"] = 0;
    gltf["materials"] = materials;
    nlohmann::json nodes = nlohmann::json::array(), meshJson = nlohmann::json::array();
    nlohmann::json accessors = nlohmann::json::array(), views = nlohmann::json::array();
    for (const TestMesh& m : meshes) {
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& p : m.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        size_t positionsOffset = bin.size();
        append(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
        size_t indicesOffset = bin.size();
        append(m.triangles.data(), m.triangles.size() * sizeof(glm::uvec3));
        size_t view = views.size();
        views.push_back(
            {{"buffer", 0}, {"byteOffset", positionsOffset}, {"byteLength", indicesOffset - positionsOffset}});
        views.push_back({{"buffer", 0}, {"byteOffset", indicesOffset}, {"byteLength", bin.size() - indicesOffset}});
        size_t accessor = accessors.size();
        accessors.push_back({{"bufferView", view}, {"componentType", 5126}, {"count", m.positions.size()},
                             {"type", "VEC3"}, {"min", vec(lo)}, {"max", vec(hi)}});
        accessors.push_back({{"bufferView", view + 1}, {"componentType", 5125},
                             {"count", 3 * m.triangles.size()}, {"type", "SCALAR"}});
        nlohmann::json attributes = {{"POSITION", accessor}};
        // A float vertex attribute of `count` elements of `type`, where the mesh has one.
        auto addAttribute = [&](const char* name, const void* data, size_t count, size_t elementBytes,
                                const char* type) {
            if (count == 0) {
                return;
            }
            size_t offset = bin.size();
            append(data, count * elementBytes);
            views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", count * elementBytes}});
            accessors.push_back(
                {{"bufferView", views.size() - 1}, {"componentType", 5126}, {"count", count}, {"type", type}});
            attributes[name] = accessors.size() - 1;
        };
        addAttribute("NORMAL", m.normals.data(), m.normals.size(), sizeof(glm::vec3), "VEC3");
        addAttribute("COLOR_0", m.colors.data(), m.colors.size(), sizeof(glm::vec4), "VEC4");
        nodes.push_back({{"mesh", meshJson.size()}});
        meshJson.push_back({{"primitives", {{{"attributes", attributes},
                                           {"indices", accessor + 1},
                                           {"material", m.material}}}}});
    }
    // glTF cameras look down their local -Z; a half turn about Y makes that +Z.
    nlohmann::json camera = {{"camera", 0}, {"translation", vec(cameraPosition)}};
    if (cameraLooksAlongPlusZ) {
        camera["rotation"] = {0.0, 1.0, 0.0, 0.0};
    }
    nodes.push_back(camera);
    for (const TestCameraNode& c : moreCameras) {
        glm::mat4 lookAt = glm::inverse(glm::lookAt(c.position, c.target, glm::vec3(0.0f, 1.0f, 0.0f)));
        glm::quat q = glm::quat_cast(glm::mat3(lookAt));
        nodes.push_back({{"name", c.name}, {"camera", 0}, {"translation", vec(c.position)}, {"rotation", {q.x, q.y, q.z, q.w}}});
    }
    for (const TestLightNode& l : lightNodes) {
        // The rotation taking the node's -Z to `direction`.
        glm::quat q = glm::rotation(glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(l.direction));
        nodes.push_back({{"translation", vec(l.position)},
                         {"rotation", {q.x, q.y, q.z, q.w}},
                         {"extensions", {{"KHR_lights_punctual", {{"light", l.light}}}}}});
    }
    nlohmann::json sceneNodes = nlohmann::json::array();
    for (size_t i = 0; i < nodes.size(); ++i) {
        sceneNodes.push_back(i);
    }
    gltf["nodes"] = nodes;
    gltf["meshes"] = meshJson;
    gltf["accessors"] = accessors;
    gltf["bufferViews"] = views;
    gltf["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}};
    if (orthographicHalfHeight > 0.0f) {
        gltf["cameras"] = {{{"type", "orthographic"},
                            {"orthographic", {{"xmag", orthographicHalfHeight * aspectRatio},
                                              {"ymag", orthographicHalfHeight}, {"znear", 0.0}, {"zfar", 100.0}}}}};
    } else {
        gltf["cameras"] = {{{"type", "perspective"},
                            {"perspective", {{"yfov", yfov}, {"aspectRatio", aspectRatio}, {"znear", 0.01}}}}};
    }
    gltf["scenes"] = {{{"nodes", sceneNodes}}};
    nlohmann::json used = nlohmann::json::array();
    for (const nlohmann::json& m : materials) {
        if (m.contains("extensions")) {
            for (auto& [key, value] : m["extensions"].items()) {
                used.push_back(key);
            }
        }
    }
    nlohmann::json rootExtensions = extensions;
    if (!lights.empty()) {
        rootExtensions["KHR_lights_punctual"] = {{"lights", lights}};
    }
    for (auto& [key, value] : rootExtensions.items()) {
        used.push_back(key);
    }
    if (!rootExtensions.empty()) {
        gltf["extensions"] = rootExtensions;
    }
    if (!used.empty()) {
        std::sort(used.begin(), used.end());
        used.erase(std::unique(used.begin(), used.end()), used.end());
        gltf["extensionsUsed"] = used;
    }
    std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), bin.size());
    std::filesystem::path file = dir / (name + ".gltf");
    std::ofstream(file) << gltf.dump(1);
    return file;
}

nlohmann::json emissiveMaterial(const std::string& name, glm::vec3 radiance, bool doubleSided) {
    float strength = std::max({radiance.x, radiance.y, radiance.z, 1.0f});
    return {{"name", name},
            {"doubleSided", doubleSided},
            {"pbrMetallicRoughness", {{"baseColorFactor", {0.0, 0.0, 0.0, 1.0}}}},
            {"emissiveFactor", vec(radiance / strength)},
            {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}};
}

nlohmann::json diffuseMaterial(const std::string& name, glm::vec3 albedo) {
    return {{"name", name}, {"pbrMetallicRoughness", {{"baseColorFactor", {albedo.x, albedo.y, albedo.z, 1.0}}}}};
}

nlohmann::json vkdrMediumMaterial(const std::string& name, glm::vec3 sigma_a, glm::vec3 sigma_s, float g) {
    return {{"name", name},
            {"extensions",
             {{"VKDR_participating_media", {{"sigma_a", vec(sigma_a)}, {"sigma_s", vec(sigma_s)}, {"g", g}}}}}};
}

nlohmann::json khrVolumeMaterial(const std::string& name, glm::vec3 attenuationColor, float attenuationDistance) {
    return {{"name", name},
            {"extensions",
             {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
              {"KHR_materials_ior", {{"ior", 1.0}}},
              {"KHR_materials_volume",
               {{"thicknessFactor", 1.0},
                {"attenuationColor", vec(attenuationColor)},
                {"attenuationDistance", attenuationDistance}}}}}};
}

}  // namespace vkdr::test
