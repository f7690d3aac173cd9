#pragma once
#include <glm/glm.hpp>

namespace vkdr {

// What a node's transform does to a mesh besides moving its vertices: whether it
// mirrors (the winding turns, glTF 2.0 "Meshes") and how it turns normals (the inverse
// transpose). Both from the linear part in double, scaled by one factor to a largest
// entry of 1, so that they hold for any float transform: the determinant of a scale of
// 1e-16 is 1e-48, below float's range, and the inverse of a scale of 1e13 holds
// entries of 1e-39.
struct MeshPlacement {
    bool mirrored = false;
    glm::dmat3 normalToWorld{1.0};  // the inverse transpose up to a positive factor

    explicit MeshPlacement(const glm::mat4& meshToWorld);
    // The unit world-space normal of `normal`, or (0, 0, 0) (the triangle's own normal)
    // for a zero or non-finite one, which some exporters write for degenerate vertices.
    glm::vec3 worldNormal(glm::vec3 normal) const;
};

}  // namespace vkdr
