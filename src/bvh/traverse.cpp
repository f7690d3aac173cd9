#include <cmath>

#include "bvh/bvh.h"

namespace vkdr {
namespace {

// Widens a box's exit distance by 2 * gamma(3) (pbrt-v4, Ize 2013) so that rounding
// in the slab test never culls a box that the exact ray passes through.
constexpr float kExitSlack = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

// A ray with what every box test needs precomputed.
struct BoxRay {
    glm::vec3 origin;
    glm::vec3 inverseDirection;  // 1 / d, so +-inf where a component is +-0
    glm::bvec3 negative;         // per axis: the ray enters through the max plane

    BoxRay(const glm::vec3& o, const glm::vec3& d)
        : origin(o), inverseDirection(1.0f / d), negative(glm::lessThan(inverseDirection, glm::vec3(0.0f))) {}

    // Where the ray enters the box, if it overlaps it somewhere in (0, tMax).
    // Entry and exit planes are chosen by the direction's sign rather than by
    // comparing distances: then a ray parallel to a slab and exactly on one of its
    // planes gets 0 * inf = NaN for that plane, which fails both comparisons below
    // and leaves the interval alone, and an empty box (min > max) is never entered.
    std::optional<float> enter(const BvhNode& node, float tMax) const {
        float tEnter = 0.0f, tExit = tMax;
        for (int axis = 0; axis < 3; ++axis) {
            float near = negative[axis] ? node.boundsMax[axis] : node.boundsMin[axis];
            float far = negative[axis] ? node.boundsMin[axis] : node.boundsMax[axis];
            float tNear = (near - origin[axis]) * inverseDirection[axis];
            float tFar = (far - origin[axis]) * inverseDirection[axis] * kExitSlack;
            if (tNear > tEnter) tEnter = tNear;
            if (tFar < tExit) tExit = tFar;
        }
        if (tEnter > tExit) return std::nullopt;
        return tEnter;
    }
};

}  // namespace

std::optional<RayHit> intersectTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& v0,
                                        const glm::vec3& v1, const glm::vec3& v2, float tMax) {
    glm::vec3 e1 = v1 - v0;
    glm::vec3 e2 = v2 - v0;
    glm::vec3 p = glm::cross(direction, e2);
    float det = glm::dot(e1, p);
    if (det == 0.0f || !std::isfinite(det)) return std::nullopt;
    float inv = 1.0f / det;
    glm::vec3 s = origin - v0;
    float b1 = glm::dot(s, p) * inv;
    glm::vec3 q = glm::cross(s, e1);
    float b2 = glm::dot(direction, q) * inv;
    float t = glm::dot(e2, q) * inv;
    if (b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f && t > 0.0f && t < tMax) return RayHit{t, 0, b1, b2};
    return std::nullopt;
}

std::optional<RayHit> closestHit(const Bvh& bvh, std::span<const glm::vec3> positions,
                                 std::span<const glm::uvec3> triangles, const glm::vec3& origin,
                                 const glm::vec3& direction, float tMax) {
    BoxRay ray(origin, direction);
    if (bvh.nodes.empty() || !ray.enter(bvh.nodes[0], tMax)) return std::nullopt;

    struct Pending {
        uint32_t node;
        float tEnter;  // skip the node if a hit closer than this turns up meanwhile
    };
    Pending stack[kBvhMaxDepth];
    int stackSize = 0;
    std::optional<RayHit> closest;
    uint32_t nodeIndex = 0;
    for (;;) {
        const BvhNode& node = bvh.nodes[nodeIndex];
        if (node.count > 0) {
            for (uint32_t i = node.firstOrChild; i < node.firstOrChild + node.count; ++i) {
                uint32_t triangle = bvh.triangleOrder[i];
                const glm::uvec3& v = triangles[triangle];
                if (auto hit = intersectTriangle(origin, direction, positions[v.x], positions[v.y], positions[v.z], tMax)) {
                    closest = *hit;
                    closest->triangle = triangle;
                    tMax = hit->t;
                }
            }
        } else {
            // Visit the nearer child first: its hits shrink tMax for the other one.
            uint32_t first = node.firstOrChild;
            std::optional<float> t0 = ray.enter(bvh.nodes[first], tMax);
            std::optional<float> t1 = ray.enter(bvh.nodes[first + 1], tMax);
            if (t0 && t1) {
                bool secondIsNearer = *t1 < *t0;
                stack[stackSize++] = secondIsNearer ? Pending{first, *t0} : Pending{first + 1, *t1};
                nodeIndex = secondIsNearer ? first + 1 : first;
                continue;
            }
            if (t0 || t1) {
                nodeIndex = t0 ? first : first + 1;
                continue;
            }
        }
        // Resume at the latest pending node that no hit found since has ruled out.
        while (stackSize > 0 && stack[stackSize - 1].tEnter >= tMax) --stackSize;
        if (stackSize == 0) return closest;
        nodeIndex = stack[--stackSize].node;
    }
}

}  // namespace vkdr
