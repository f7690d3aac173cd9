#include "scene/medium_at.h"

#include <vector>

#include "scene/boundary_rays.h"

namespace vkdr {

int32_t mediumAt(const Scene& scene, glm::vec3 point) {
    std::vector<uint32_t> boundaryTriangles;
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.materials[scene.triangleMaterial[t]].isMediumBoundary()) {
            boundaryTriangles.push_back(t);
        }
    }
    std::optional<BoundaryHit> hit =
        closestBoundaryHit(scene, boundaryTriangles, point, kContainmentRayDirection);
    if (!hit) {
        return scene.sceneMedium;
    }
    if (hit->leaving) {
        return scene.materials[scene.triangleMaterial[hit->triangle]].interiorMedium;
    }
    return scene.triangleOutsideMedium[hit->triangle];
}

}  // namespace vkdr
