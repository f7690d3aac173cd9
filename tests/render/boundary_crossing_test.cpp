// A cube of grey medium that only scatters, under a background of 1: every path enters
// it, scatters, and leaves it again with its throughput whole, so every pixel is 1. A
// path that takes the wrong side of a crossing at one of the cube's edges carries the
// medium outside, where it never leaves the medium again and returns nothing. Far from
// the origin float's rounding is a larger part of the cube, and so are such crossings:
// 1e5 away about 0.5 % of the paths met one.
#include "furnace_scene.h"
#include "render_test_support.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

class BoundaryCrossingTest : public RenderTest {};

TEST_F(BoundaryCrossingTest, EveryPathLeavesAGreyCubeFarFromTheOrigin) {
    for (const float distance : {1.0e5f, 1.0e6f}) {
        SCOPED_TRACE("cube " + std::to_string(distance) + " from the origin");
        const glm::vec3 centre(distance);
        TestGltf g;
        g.materials = {vkdrMediumMaterial("grey", glm::vec3(0.0f), glm::vec3(2.0f), 0.0f)};
        g.meshes = {box(centre - glm::vec3(1.0f), centre + glm::vec3(1.0f), 0)};
        g.extensions["VKDR_background"] = {{"radiance", {1.0, 1.0, 1.0}}};
        g.cameraPosition = centre - glm::vec3(0.0f, 0.0f, 4.0f);
        auto file = g.write(tempDir(), "cube");
        // Depth enough that no path is cut short: in a cube of optical half-width 2 a
        // path leaves after tens of collisions.
        const Image image = renderFile(file, {.width = 32, .height = 32, .spp = 64, .maxDepth = 1000});
        expectUniformRadiance(image, glm::dvec3(1.0));
    }
}

}  // namespace
}  // namespace vkdr::test
