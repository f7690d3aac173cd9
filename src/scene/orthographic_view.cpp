#include "scene/orthographic_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "scene/surface_reach.h"

namespace vkdr {
namespace {

struct ViewRectangle {
    double halfWidth, halfHeight;

    // Whether the segment from a to b meets the closed rectangle (Liang-Barsky clipping).
    bool meetsSegment(glm::dvec2 a, glm::dvec2 b) const {
        double enter = 0.0, leave = 1.0;
        const glm::dvec2 step = b - a;
        const std::array<std::pair<double, double>, 4> sides = {{{-step.x, a.x + halfWidth},
                                                                {step.x, halfWidth - a.x},
                                                                {-step.y, a.y + halfHeight},
                                                                {step.y, halfHeight - a.y}}};
        for (const auto& [towards, room] : sides) {
            if (towards == 0.0) {
                if (room < 0.0) return false;
                continue;
            }
            const double t = room / towards;
            if (towards < 0.0) enter = std::max(enter, t);
            else leave = std::min(leave, t);
            if (enter > leave) return false;
        }
        return true;
    }
};

// A triangle without area holds no point but those of its edges.
bool insideTriangle(glm::dvec2 p, const std::array<glm::dvec2, 3>& v) {
    auto cross = [](glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; };
    if (cross(v[1] - v[0], v[2] - v[0]) == 0.0) return false;
    const double s0 = cross(v[1] - v[0], p - v[0]), s1 = cross(v[2] - v[1], p - v[1]),
                 s2 = cross(v[0] - v[2], p - v[2]);
    return (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) || (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0);
}

// Whether a triangle, in camera coordinates, meets the view's rectangle on the plane z = 0.
bool meetsView(const std::array<glm::dvec3, 3>& v, const ViewRectangle& view, double onPlane) {
    const bool coplanar =
        std::all_of(v.begin(), v.end(), [&](const glm::dvec3& p) { return std::abs(p.z) <= onPlane; });
    if (coplanar) {
        const std::array<glm::dvec2, 3> flat = {glm::dvec2(v[0]), glm::dvec2(v[1]), glm::dvec2(v[2])};
        for (int i = 0; i < 3; ++i) {
            if (view.meetsSegment(flat[i], flat[(i + 1) % 3])) return true;
        }
        return insideTriangle(glm::dvec2(0.0), flat);  // the rectangle wholly inside the triangle
    }
    // Where the triangle cuts the plane: vertices on it, and edges whose ends lie on either side.
    std::vector<glm::dvec2> cut;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 a = v[i], b = v[(i + 1) % 3];
        if (std::abs(a.z) <= onPlane) cut.emplace_back(a);
        if ((a.z < -onPlane && b.z > onPlane) || (a.z > onPlane && b.z < -onPlane)) {
            cut.push_back(glm::dvec2(a + (b - a) * (a.z / (a.z - b.z))));
        }
    }
    for (size_t i = 0; i < cut.size(); ++i) {
        for (size_t j = i; j < cut.size(); ++j) {
            if (view.meetsSegment(cut[i], cut[j])) return true;
        }
    }
    return false;
}

}  // namespace

std::optional<uint32_t> boundaryAcrossOrthographicView(const Scene& scene, const Camera& camera, double halfWidth,
                                                       double halfHeight) {
    const glm::dmat4 cameraToWorld(camera.cameraToWorld);
    const glm::dvec3 origin(cameraToWorld[3]);
    // The rays' own mapping (generate.comp) takes the camera's axes as they are.
    const glm::dmat3 worldToCamera = glm::inverse(glm::dmat3(cameraToWorld));
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const uint32_t material = scene.triangleMaterial[t];
        if (!scene.materials[material].isMediumBoundary()) continue;
        const std::array<glm::dvec3, 3> world = {glm::dvec3(scene.positions[scene.triangles[t].x]),
                                                 glm::dvec3(scene.positions[scene.triangles[t].y]),
                                                 glm::dvec3(scene.positions[scene.triangles[t].z])};
        const double reach =
            kOnSurfaceRelative * std::max({coordinateMagnitude(origin), coordinateMagnitude(world[0]),
                                           coordinateMagnitude(world[1]), coordinateMagnitude(world[2]), halfWidth,
                                           halfHeight});
        std::array<glm::dvec3, 3> local;
        for (int i = 0; i < 3; ++i) local[i] = worldToCamera * (world[i] - origin);
        if (meetsView(local, ViewRectangle{halfWidth + reach, halfHeight + reach}, reach)) return material;
    }
    return std::nullopt;
}

}  // namespace vkdr
