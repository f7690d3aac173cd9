#include "scene/camera_on_boundary.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "core/format_text.h"
#include "scene/surface_reach.h"

namespace vkdr {
namespace {

// Barycentric slack, so that a camera on an edge belongs to the triangles on both sides.
constexpr double kBarycentricSlack = 1e-6;

// How far `p` is from the triangle's plane, where its projection onto that plane falls
// inside the triangle; a negative value where it falls outside (or the triangle has no area).
double distanceAbove(const glm::dvec3& p, const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2) {
    const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0;
    const glm::dvec3 normal = glm::cross(e1, e2);
    const double area2 = glm::dot(normal, normal);
    if (!(area2 > 0.0)) return -1.0;
    const glm::dvec3 toPoint = p - v0;
    const double b1 = glm::dot(glm::cross(toPoint, e2), normal) / area2;
    const double b2 = glm::dot(glm::cross(e1, toPoint), normal) / area2;
    if (b1 < -kBarycentricSlack || b2 < -kBarycentricSlack || b1 + b2 > 1.0 + kBarycentricSlack) return -1.0;
    return std::abs(glm::dot(toPoint, normal)) / std::sqrt(area2);
}

}  // namespace

std::vector<std::string> camerasOnMediumBoundaries(const Scene& scene) {
    std::vector<std::string> warnings;
    for (const Camera& camera : scene.cameras) {
        const glm::dvec3 position(camera.cameraToWorld[3]);
        for (size_t t = 0; t < scene.triangles.size(); ++t) {
            const Material& material = scene.materials[scene.triangleMaterial[t]];
            if (!material.isMediumBoundary()) continue;
            const glm::dvec3 v0(scene.positions[scene.triangles[t].x]);
            const glm::dvec3 v1(scene.positions[scene.triangles[t].y]);
            const glm::dvec3 v2(scene.positions[scene.triangles[t].z]);
            const double distance = distanceAbove(position, v0, v1, v2);
            const double reach =
                kOnSurfaceRelative * std::max({coordinateMagnitude(position), coordinateMagnitude(v0),
                                                coordinateMagnitude(v1), coordinateMagnitude(v2)});
            if (distance < 0.0 || distance > reach) continue;
            warnings.push_back(formatText(
                "camera '%s' lies on the boundary of medium '%s' (material '%s'), %g from its surface: rays from "
                "it may start on either side, so some pixels would see the medium and others not; move the "
                "camera off the surface",
                camera.name.c_str(), scene.media[size_t(material.interiorMedium)].name.c_str(),
                material.name.c_str(), distance));
            break;
        }
    }
    return warnings;
}

}  // namespace vkdr
