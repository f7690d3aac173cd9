#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

namespace vkdr::test {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;

    void addTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        uint32_t first = uint32_t(positions.size());
        positions.insert(positions.end(), {a, b, c});
        triangles.push_back({first, first + 1, first + 2});
    }
};

// Triangles with corners scattered around random centres in [0, 1]^3, each corner
// within `size` of its centre.
inline Mesh randomSoup(size_t count, float size, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-size, size);
    auto randomPoint = [&] { return glm::vec3(unit(rng), unit(rng), unit(rng)); };
    auto near = [&](const glm::vec3& c) { return c + glm::vec3(offset(rng), offset(rng), offset(rng)); };
    Mesh mesh;
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 centre = randomPoint();
        mesh.addTriangle(near(centre), near(centre), near(centre));
    }
    return mesh;
}

// A cells x cells grid over [0, 1]^2 in the plane z = 0, two triangles per cell,
// vertices shared between neighbouring cells.
inline Mesh gridMesh(uint32_t cells) {
    Mesh mesh;
    for (uint32_t y = 0; y <= cells; ++y)
        for (uint32_t x = 0; x <= cells; ++x) mesh.positions.push_back(glm::vec3(x, y, 0.0f) / float(cells));
    auto vertex = [cells](uint32_t x, uint32_t y) { return y * (cells + 1) + x; };
    for (uint32_t y = 0; y < cells; ++y)
        for (uint32_t x = 0; x < cells; ++x) {
            mesh.triangles.push_back({vertex(x, y), vertex(x + 1, y), vertex(x + 1, y + 1)});
            mesh.triangles.push_back({vertex(x, y), vertex(x + 1, y + 1), vertex(x, y + 1)});
        }
    return mesh;
}

// Zero-area triangles: a repeated corner, three collinear corners, a single point.
inline void addDegenerateTriangles(Mesh& mesh, size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto randomPoint = [&] { return glm::vec3(unit(rng), unit(rng), unit(rng)); };
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 a = randomPoint(), b = randomPoint();
        switch (i % 3) {
        case 0: mesh.addTriangle(a, a, b); break;
        case 1: mesh.addTriangle(a, 0.5f * (a + b), b); break;
        default: mesh.addTriangle(a, a, a); break;
        }
    }
}

}  // namespace vkdr::test
