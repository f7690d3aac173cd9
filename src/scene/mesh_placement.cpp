#include "scene/mesh_placement.h"

#include <algorithm>
#include <cmath>

namespace vkdr {

MeshPlacement::MeshPlacement(const glm::mat4& meshToWorld) {
    glm::dmat3 linear(meshToWorld);
    double largest = 0.0;
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) largest = std::max(largest, std::abs(linear[column][row]));
    }
    if (largest > 0.0 && std::isfinite(largest)) linear /= largest;
    const double determinant = glm::determinant(linear);
    mirrored = determinant < 0.0;
    // The cofactor matrix, determinant x inverse transpose, needs no division: its
    // columns are the cross products of the other two columns.
    const glm::dmat3 cofactors(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                               glm::cross(linear[0], linear[1]));
    normalToWorld = mirrored ? -cofactors : cofactors;
}

glm::vec3 MeshPlacement::worldNormal(glm::vec3 normal) const {
    const glm::dvec3 world = normalToWorld * glm::dvec3(normal);
    const double length = glm::length(world);
    const glm::dvec3 unit = world / length;
    const bool usable = length > 0.0 && std::isfinite(unit.x) && std::isfinite(unit.y) && std::isfinite(unit.z);
    return usable ? glm::vec3(unit) : glm::vec3(0.0f);
}

}  // namespace vkdr
