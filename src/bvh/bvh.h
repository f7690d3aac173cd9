#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace vkdr {

// 32 bytes, laid out as the GPU reads it (two vec4s): an interior node (count == 0)
// has its children at nodes[firstOrChild] and nodes[firstOrChild + 1]; a leaf holds
// the triangles bvh.triangleOrder[firstOrChild .. firstOrChild + count).
struct BvhNode {
    glm::vec3 boundsMin;
    uint32_t firstOrChild;
    glm::vec3 boundsMax;
    uint32_t count;
};
static_assert(sizeof(BvhNode) == 32);

// No path from the root to a leaf has more than this many edges, so a traversal stack
// of kBvhMaxDepth entries never overflows (the build falls back to median splits
// rather than let a pathological SAH tree grow deeper).
inline constexpr uint32_t kBvhMaxDepth = 64;
inline constexpr uint32_t kBvhMaxLeafTriangles = 8;

// With no triangles, nodes holds only the root: count 0 and an empty box
// (boundsMin > boundsMax) that no ray enters. Traversal must test the root's box
// before reading its children.
struct Bvh {
    std::vector<BvhNode> nodes;          // nodes[0] is the root
    std::vector<uint32_t> triangleOrder; // leaf order -> index into the scene's triangles
};

// SAH build over the triangles' bounds: binned in large nodes (from a sample in the
// largest), exact in subtrees of at most 64 triangles (exact_subtree.h), parallel over
// subtrees. Deterministic: the same input gives the same tree whatever the thread
// count or scheduling.
// Throws std::invalid_argument for a vertex index out of range.
Bvh buildBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);

struct RayHit {
    float t;            // distance along the (not necessarily unit) direction
    uint32_t triangle;  // index into the scene's triangles
    float b1, b2;       // barycentrics of vertices 1 and 2
};

// The watertight test of shaders/lib/intersect_triangle.glsl, formula for formula.
// Two-sided; hits with t in (0, tMax). The returned hit's triangle is 0: the caller
// knows which triangle it tested.
std::optional<RayHit> intersectTriangle(const glm::vec3& origin, const glm::vec3& direction,
                                        const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                                        float tMax);

// Closest hit with t in (0, tMax).
std::optional<RayHit> closestHit(const Bvh& bvh, std::span<const glm::vec3> positions,
                                 std::span<const glm::uvec3> triangles, const glm::vec3& origin,
                                 const glm::vec3& direction, float tMax);

}  // namespace vkdr
