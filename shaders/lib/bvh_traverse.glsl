// Traversal of the binned-SAH BVH built on the host (src/bvh/bvh.h) for the closest
// hit, or for shadow rays any opaque hit: one ray per invocation, a short stack, nearer
// child first.
#ifndef VKDR_BVH_TRAVERSE_GLSL
#define VKDR_BVH_TRAVERSE_GLSL
#include "constants.glsl"
#include "intersect_triangle.glsl"
#include "scene_access.glsl"

const uint kBvhStackSize = 64u;
// Bounds the loop so a corrupt tree cannot hang the device; far above any real
// traversal, and below lavapipe's silent cap of ~65k iterations per subgroup.
const uint kMaxTraversalSteps = 16384u;

struct TraceHit {
    float t;        // kFar on a miss
    float b1;
    float b2;
    uint triangle;  // BVH-order index, kNoHit on a miss
};

// Entry distance of the ray into a box, or kFar when it misses it within tMax.
float boxEntry(vec3 boxMin, vec3 boxMax, vec3 origin, vec3 invDirection, float tMax) {
    vec3 t0 = (boxMin - origin) * invDirection;
    vec3 t1 = (boxMax - origin) * invDirection;
    vec3 tNear = min(t0, t1);
    vec3 tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0f));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
    return enter <= exit ? enter : kFar;
}

vec3 safeInverse(vec3 d) {
    const float tiny = 1.0e-30f;
    return vec3(1.0f) / vec3(abs(d.x) > tiny ? d.x : (d.x >= 0.0f ? tiny : -tiny),
                             abs(d.y) > tiny ? d.y : (d.y >= 0.0f ? tiny : -tiny),
                             abs(d.z) > tiny ? d.z : (d.z >= 0.0f ? tiny : -tiny));
}

// The node's children (y == 0) or triangles: x is its first child or triangle, y its
// triangle count, in the fourth lanes of its two vec4s.
uvec2 nodeLink(uint node) {
    return uvec2(floatBitsToUint(P.bvhNodes.v[2u * node].w), floatBitsToUint(P.bvhNodes.v[2u * node + 1u].w));
}

// Whether the segment from `origin` to `end` may reach the plane of the triangle (v0,
// v1, v2). It cannot where its origin is off the plane and its end on the origin's side
// or on the plane, beyond the rounding of either side: then it cannot meet the triangle
// short of its end, whatever the intersection test says. A ray that grazes a triangle
// much larger than itself has its intersection's distance rounded in proportion to the
// triangle's size over the sine of the angle: a shadow ray towards a light placed on a
// surface. The normal is the cross product of the two edges at the vertex opposite the
// longest, the best conditioned pair; the rounding of a point's side is that of the
// normal times the point's distance from that vertex, plus that of the positions
// themselves (the largest coordinate of the vertices and the end), each a few machine
// epsilons.
bool segmentMayReachPlane(vec3 origin, vec3 end, vec3 v0, vec3 v1, vec3 v2) {
    const float kRounding = 8.0f * 1.1920929e-7f;  // 8 times float's machine epsilon
    vec3 e01 = v1 - v0, e12 = v2 - v1, e20 = v0 - v2;
    float l01 = dot(e01, e01), l12 = dot(e12, e12), l20 = dot(e20, e20);
    vec3 corner = v0, ea = e01, eb = -e20;  // at v0, opposite the edge v1 v2
    if (l01 >= l12 && l01 >= l20) {
        corner = v2;  // opposite the edge v0 v1
        ea = e20;
        eb = -e12;
    } else if (l20 >= l12) {
        corner = v1;  // opposite the edge v2 v0
        ea = e12;
        eb = -e01;
    }
    vec3 normal = cross(ea, eb);
    float originSide = dot(normal, origin - corner);
    float endSide = dot(normal, end - corner);
    float edges = length(ea) * length(eb);
    float positions = maxComponent(max(max(abs(v0), abs(v1)), max(abs(v2), abs(end)))) * length(normal);
    float originRounding = kRounding * (edges * length(origin - corner) + positions);
    float endRounding = kRounding * (edges * length(end - corner) + positions);
    bool originOff = abs(originSide) > originRounding;
    bool endNotPast = (originSide > 0.0f ? endSide : -endSide) >= -endRounding;
    return !(originOff && endNotPast);
}

// The closest hit within tMax, passing over the triangles in `skipped` (kNoHit: none):
// the one a ray leaves from and the emitter triangle a shadow ray ends on, which it
// would meet at a rounded distance near 0 or tMax. With stopAtOpaque, the first hit
// found on an opaque triangle ends the search instead: a shadow ray is blocked by any
// opaque surface on its way, whichever is nearest, and only medium boundaries need the
// closest hit. Such a ray ends at tMax where that is finite, and an opaque triangle
// whose plane it cannot reach (segmentMayReachPlane) is passed over.
TraceHit traceClosest(vec3 origin, vec3 direction, float tMax, bool stopAtOpaque, uvec2 skipped) {
    TraceHit best = TraceHit(tMax, 0.0f, 0.0f, kNoHit);
    bool endsAtTMax = tMax < kFar;
    vec3 end = origin + direction * (endsAtTMax ? tMax : 0.0f);
    vec3 invDirection = safeInverse(direction);
    uint stack[kBvhStackSize];
    uint stackSize = 0u;
    uint node = 0u;
    uint steps = 0u;
    bool done = false;
    // Each round descends to a leaf, then tests its triangles. The lanes of a subgroup
    // that reach their leaves at different steps wait for each other and test them
    // together, instead of splitting into interior and leaf work at every step (Aila
    // and Laine's "while-while" order).
    while (!done && steps < kMaxTraversalSteps) {
        uvec2 link = nodeLink(node);
        while (link.y == 0u && !done && steps < kMaxTraversalSteps) {
            ++steps;
            uint left = link.x;
            uint right = link.x + 1u;
            float tLeft = boxEntry(P.bvhNodes.v[2u * left].xyz, P.bvhNodes.v[2u * left + 1u].xyz,
                                   origin, invDirection, best.t);
            float tRight = boxEntry(P.bvhNodes.v[2u * right].xyz, P.bvhNodes.v[2u * right + 1u].xyz,
                                    origin, invDirection, best.t);
            bool hitLeft = tLeft < kFar;
            bool hitRight = tRight < kFar;
            if (hitLeft && hitRight) {
                bool leftFirst = tLeft <= tRight;
                if (stackSize < kBvhStackSize) {
                    stack[stackSize++] = leftFirst ? right : left;
                } else {
                    flagTruncatedLoop();
                }
                node = leftFirst ? left : right;
            } else if (hitLeft || hitRight) {
                node = hitLeft ? left : right;
            } else {
                done = stackSize == 0u;
                if (!done) {
                    node = stack[--stackSize];
                }
            }
            if (!done) {
                link = nodeLink(node);
            }
        }
        if (done || link.y == 0u) {
            continue;
        }
        ++steps;
        for (uint i = link.x; i < link.x + link.y; ++i) {
            if (i == skipped.x || i == skipped.y) {
                continue;
            }
            vec3 v0 = P.triangleVertices.v[3u * i].xyz;
            vec3 v1 = P.triangleVertices.v[3u * i + 1u].xyz;
            vec3 v2 = P.triangleVertices.v[3u * i + 2u].xyz;
            vec3 hit = intersectTriangle(origin, direction, v0, v1, v2, best.t);
            if (hit.x <= 0.0f) {
                continue;
            }
            if (stopAtOpaque && isOpaque(i)) {
                if (!endsAtTMax || segmentMayReachPlane(origin, end, v0, v1, v2)) {
                    return TraceHit(hit.x, hit.y, hit.z, i);
                }
            } else {
                best = TraceHit(hit.x, hit.y, hit.z, i);
            }
        }
        done = stackSize == 0u;
        if (!done) {
            node = stack[--stackSize];
        }
    }
    if (!done) {
        flagTruncatedLoop();
    }
    if (best.triangle == kNoHit) {
        best.t = kFar;
    }
    return best;
}

#endif
