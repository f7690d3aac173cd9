#include <algorithm>
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

// a * b - c * d with one rounding (Kahan's algorithm with fused multiply-adds).
float differenceOfProducts(float a, float b, float c, float d) {
    float cd = c * d;
    return std::fma(a, b, -cd) + std::fma(-c, d, cd);
}

// n machine epsilons' worth of relative rounding, bounded (pbrt's gamma).
float roundingGamma(float n) {
    constexpr float kUnitRoundoff = 5.9604645e-8f;  // 2^-24
    return n * kUnitRoundoff / (1.0f - n * kUnitRoundoff);
}

}  // namespace

std::optional<RayHit> intersectTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& v0,
                                        const glm::vec3& v1, const glm::vec3& v2, float tMax) {
    glm::vec3 a = glm::abs(direction);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    glm::vec3 d(direction[kx], direction[ky], direction[kz]);
    glm::vec3 r0 = v0 - origin, r1 = v1 - origin, r2 = v2 - origin;
    glm::vec3 p0(r0[kx], r0[ky], r0[kz]);
    glm::vec3 p1(r1[kx], r1[ky], r1[kz]);
    glm::vec3 p2(r2[kx], r2[ky], r2[kz]);
    float sx = -d.x / d.z, sy = -d.y / d.z, sz = 1.0f / d.z;
    p0.x += sx * p0.z;
    p0.y += sy * p0.z;
    p1.x += sx * p1.z;
    p1.y += sy * p1.z;
    p2.x += sx * p2.z;
    p2.y += sy * p2.z;
    float e0 = differenceOfProducts(p1.x, p2.y, p1.y, p2.x);
    float e1 = differenceOfProducts(p2.x, p0.y, p2.y, p0.x);
    float e2 = differenceOfProducts(p0.x, p1.y, p0.y, p1.x);
    if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return std::nullopt;
    float det = e0 + e1 + e2;
    if (det == 0.0f || !std::isfinite(det)) return std::nullopt;
    p0.z *= sz;
    p1.z *= sz;
    p2.z *= sz;
    float tScaled = e0 * p0.z + e1 * p1.z + e2 * p2.z;
    if (det < 0.0f ? (tScaled >= 0.0f || tScaled < tMax * det) : (tScaled <= 0.0f || tScaled > tMax * det)) {
        return std::nullopt;
    }
    float invDet = 1.0f / det;
    float t = tScaled * invDet;
    float maxZ = std::max({std::abs(p0.z), std::abs(p1.z), std::abs(p2.z)});
    float maxX = std::max({std::abs(p0.x), std::abs(p1.x), std::abs(p2.x)});
    float maxY = std::max({std::abs(p0.y), std::abs(p1.y), std::abs(p2.y)});
    float deltaZ = roundingGamma(3.0f) * maxZ;
    float deltaX = roundingGamma(5.0f) * (maxX + maxZ);
    float deltaY = roundingGamma(5.0f) * (maxY + maxZ);
    float deltaE = 2.0f * (roundingGamma(2.0f) * maxX * maxY + deltaY * maxX + deltaX * maxY);
    float maxE = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
    float deltaT = 3.0f * (roundingGamma(3.0f) * maxE * maxZ + deltaE * maxZ + deltaZ * maxE) * std::abs(invDet);
    if (!(t > deltaT) || !(t < tMax)) return std::nullopt;
    return RayHit{t, 0, e1 * invDet, e2 * invDet};
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
