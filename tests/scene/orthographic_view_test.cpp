// Which medium boundaries cross an orthographic camera's view: the rectangle of its XY
// plane its rays start from. Triangles placed by hand about a camera at (1, 2, 3) turned
// a quarter turn about +Y (its view spans world z, its plane is x = 1).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/orthographic_view.h"

namespace vkdr {
namespace {

constexpr double kHalfWidth = 2.0, kHalfHeight = 1.0;

Camera turnedCamera() {
    Camera camera;
    camera.cameraToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
    camera.orthographicHalfHeight = float(kHalfHeight);
    return camera;
}

// One boundary triangle with the given corners in the camera's own coordinates (x across
// the view, y up it, z along the camera's back), and one surface triangle that spans the
// whole view and never counts.
std::optional<uint32_t> crossing(const std::array<glm::vec3, 3>& local) {
    const Camera camera = turnedCamera();
    Scene scene;
    scene.materials.resize(2);
    scene.materials[1].interiorMedium = 0;
    for (const glm::vec3& corner : local) {
        scene.positions.push_back(glm::vec3(camera.cameraToWorld * glm::vec4(corner, 1)));
    }
    for (const glm::vec3& corner : {glm::vec3(-9, -9, 0), glm::vec3(9, -9, 0), glm::vec3(0, 9, 0)}) {
        scene.positions.push_back(glm::vec3(camera.cameraToWorld * glm::vec4(corner, 1)));
    }
    scene.triangles = {{3, 4, 5}, {0, 1, 2}};
    scene.triangleMaterial = {0, 1};
    return boundaryAcrossOrthographicView(scene, camera, kHalfWidth, kHalfHeight);
}

TEST(OrthographicView, BoundariesThatCrossTheViewAndThoseThatDoNot) {
    // Piercing the view's middle, no edge of the triangle near the view's outline.
    EXPECT_EQ(crossing({glm::vec3(-0.5f, -0.5f, -1), glm::vec3(0.5f, -0.5f, -1), glm::vec3(0, 0.5f, 1)}), 1u);
    // Across one side of the view only.
    EXPECT_EQ(crossing({glm::vec3(1.5f, -5, -1), glm::vec3(1.5f, 5, -1), glm::vec3(1.5f, 0, 1)}), 1u);
    // Cutting the plane beside the view (x beyond 2), or before or behind it.
    EXPECT_FALSE(crossing({glm::vec3(2.5f, -5, -1), glm::vec3(2.5f, 5, -1), glm::vec3(2.5f, 0, 1)}));
    EXPECT_FALSE(crossing({glm::vec3(-1, -1, -1), glm::vec3(1, -1, -1), glm::vec3(0, 1, -2)}));
    EXPECT_FALSE(crossing({glm::vec3(-1, -1, 0.5f), glm::vec3(1, -1, 0.5f), glm::vec3(0, 1, 2)}));
    // Touching the view's corner with a vertex.
    EXPECT_EQ(crossing({glm::vec3(2, 1, 0), glm::vec3(3, 1, -1), glm::vec3(3, 2, 1)}), 1u);
    // In the plane: wholly around the view, overlapping one corner, and beside it.
    EXPECT_EQ(crossing({glm::vec3(-9, -9, 0), glm::vec3(9, -9, 0), glm::vec3(0, 9, 0)}), 1u);
    EXPECT_EQ(crossing({glm::vec3(1.5f, 0.5f, 0), glm::vec3(3, 0.5f, 0), glm::vec3(3, 3, 0)}), 1u);
    EXPECT_FALSE(crossing({glm::vec3(2.5f, 0, 0), glm::vec3(4, 0, 0), glm::vec3(4, 3, 0)}));
    // In the plane without area: a point far off, a sliver on a line through the view
    // beside it; a sliver across the view crosses it.
    EXPECT_FALSE(crossing({glm::vec3(9, 9, 0), glm::vec3(9, 9, 0), glm::vec3(9, 9, 0)}));
    EXPECT_FALSE(crossing({glm::vec3(5, 0, 0), glm::vec3(6, 0, 0), glm::vec3(7, 0, 0)}));
    EXPECT_EQ(crossing({glm::vec3(-5, 0, 0), glm::vec3(0, 0, 0), glm::vec3(5, 0, 0)}), 1u);
    // Within 1e-5 of the coordinates' magnitude (a few units here) of the view's side,
    // and well beyond it.
    EXPECT_EQ(crossing({glm::vec3(2.00001f, -5, -1), glm::vec3(2.00001f, 5, -1), glm::vec3(2.00001f, 0, 1)}), 1u);
    EXPECT_FALSE(crossing({glm::vec3(2.001f, -5, -1), glm::vec3(2.001f, 5, -1), glm::vec3(2.001f, 0, 1)}));
}

}  // namespace
}  // namespace vkdr
