#include "scene/boundary_rays.h"


namespace vkdr {
namespace {

// Moller-Trumbore in double precision; returns the ray parameter of the hit.
std::optional<double> intersect(glm::dvec3 origin, glm::dvec3 direction, glm::dvec3 p0,
                                glm::dvec3 p1, glm::dvec3 p2) {
    glm::dvec3 edge1 = p1 - p0;
    glm::dvec3 edge2 = p2 - p0;
    glm::dvec3 pvec = glm::cross(direction, edge2);
    double determinant = glm::dot(edge1, pvec);
    if (determinant == 0.0) {
        return std::nullopt;  // parallel to the plane, or a degenerate triangle
    }
    double inverse = 1.0 / determinant;
    glm::dvec3 tvec = origin - p0;
    double u = glm::dot(tvec, pvec) * inverse;
    if (u < 0.0 || u > 1.0) {
        return std::nullopt;
    }
    glm::dvec3 qvec = glm::cross(tvec, edge1);
    double v = glm::dot(direction, qvec) * inverse;
    if (v < 0.0 || u + v > 1.0) {
        return std::nullopt;
    }
    double t = glm::dot(edge2, qvec) * inverse;
    return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

}  // namespace

std::optional<BoundaryHit> closestBoundaryHit(const Scene& scene,
                                              std::span<const uint32_t> triangles,
                                              glm::dvec3 origin, glm::dvec3 direction) {
    std::optional<BoundaryHit> closest;
    for (uint32_t triangle : triangles) {
        glm::uvec3 corners = scene.triangles[triangle];
        glm::dvec3 p0 = scene.positions[corners.x];
        glm::dvec3 p1 = scene.positions[corners.y];
        glm::dvec3 p2 = scene.positions[corners.z];
        std::optional<double> t = intersect(origin, direction, p0, p1, p2);
        if (t && (!closest || *t < closest->t)) {
            glm::dvec3 normal = glm::cross(p1 - p0, p2 - p0);
            closest = BoundaryHit{triangle, *t, glm::dot(normal, direction) > 0.0};
        }
    }
    return closest;
}

bool insideClosedMesh(const Scene& scene, std::span<const uint32_t> triangles, glm::dvec3 point) {
    std::optional<BoundaryHit> hit =
        closestBoundaryHit(scene, triangles, point, kContainmentRayDirection);
    return hit && hit->leaving;
}

}  // namespace vkdr
