#include "side_lit_medium.h"

namespace vkdr::test {

DensityGrid gridOverMediumBox(int voxels) {
    DensityGrid grid;
    grid.name = "density";
    grid.size = glm::ivec3(voxels);
    const double edge = 1.2 / (voxels - 1);
    grid.indexToLocal = glm::dmat4(glm::dvec4(edge, 0, 0, 0), glm::dvec4(0, edge, 0, 0), glm::dvec4(0, 0, edge, 0),
                                   glm::dvec4(-0.6, -0.6, 1.0, 1.0));
    return grid;
}

TestMesh sideEmitter(int material) {
    TestMesh side = quadZ(0.0f, 0.0f, 0.4f, 0.0f, true, material);
    for (glm::vec3& p : side.positions) {
        // Swapping x and z mirrors the square into the plane x = 1.5, facing -x.
        p = glm::vec3(1.5f, p.y, 1.6f + p.x);
    }
    return side;
}

}  // namespace vkdr::test
