#pragma once
#include <cstdint>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkdr {

// Brute-force ray casts against a few triangles, for the load-time questions "which
// medium is this point in?". Medium boundaries are few and small; the renderer's BVH
// does the heavy lifting elsewhere.

// Not aligned with any axis, so rays from points on axis-aligned geometry do not graze
// edges or faces.
inline const glm::dvec3 kContainmentRayDirection =
    glm::normalize(glm::dvec3(0.5377, 0.8261, 0.1687));

struct BoundaryHit {
    uint32_t triangle = 0;
    double t = 0.0;
    bool leaving = false;  // the ray crosses from the back (enclosed) side to the front
};

// Closest hit with t > 0 among `triangles` (indices into scene.triangles).
std::optional<BoundaryHit> closestBoundaryHit(const Scene& scene,
                                              std::span<const uint32_t> triangles,
                                              glm::dvec3 origin, glm::dvec3 direction);

// Whether `point` lies inside a closed mesh wound outwards: the first surface a ray
// from the point meets is then seen from its back.
bool insideClosedMesh(const Scene& scene, std::span<const uint32_t> triangles, glm::dvec3 point);

}  // namespace vkdr
