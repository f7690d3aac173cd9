#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace vkdr {

// One vertex of the interleaved vertex buffer views (POSITION at byte 0, TEXCOORD_0 at 12).
struct Vertex {
    glm::vec3 position;
    glm::vec2 uv;
};
static_assert(sizeof(Vertex) == 20);

// A square grid of bumpy UV spheres resting on a floor, sized so the total triangle
// count comes close to a budget. Spheres are generated one at a time, so a scene of any
// size streams out in constant memory.
class SphereGrid {
public:
    // `floorHalfSize`: the grid covers [-floorHalfSize, floorHalfSize] in x and z at y = 0.
    // A sphere's radius is at most `maxRadius`, so that few large spheres stay clear of
    // what hangs above them (the room's light).
    SphereGrid(uint64_t triangleBudget, float floorHalfSize, float maxRadius);

    uint64_t sphereCount() const { return uint64_t(spheresPerSide_) * spheresPerSide_; }
    uint32_t verticesPerSphere() const { return (bands_ + 1) * (segments_ + 1); }
    // The pole bands have one triangle per segment, the others two.
    uint32_t trianglesPerSphere() const { return 2 * segments_ * (bands_ - 1); }
    uint64_t vertexCount() const { return sphereCount() * verticesPerSphere(); }
    uint64_t triangleCount() const { return sphereCount() * trianglesPerSphere(); }

    // Replaces `out` with sphere k's vertices / its triangles' vertex indices (offset by
    // the vertices of the spheres before it), wound counter-clockwise seen from outside.
    void sphereVertices(uint64_t sphere, std::vector<Vertex>& out) const;
    void sphereIndices(uint64_t sphere, std::vector<uint32_t>& out) const;

private:
    uint32_t spheresPerSide_ = 1;
    uint32_t bands_ = 2;     // latitude bands, pole to pole
    uint32_t segments_ = 3;  // longitude segments
    float spacing_ = 1.0f;   // between sphere centres
    float radius_ = 0.5f;
    float floorHalfSize_ = 1.0f;
};

}  // namespace vkdr
