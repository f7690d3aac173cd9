#include "furnace_scene.h"

#include <gtest/gtest.h>

#include "render_test_support.h"

namespace vkdr::test {

TestGltf furnace(glm::vec3 albedo) {
    nlohmann::json walls = emissiveMaterial("walls", kFurnaceLe, true);
    walls["pbrMetallicRoughness"]["baseColorFactor"] = {albedo.x, albedo.y, albedo.z, 1.0};
    TestGltf g;
    g.materials = {walls};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0)};
    g.cameraPosition = glm::vec3(0.1f, -0.2f, -0.3f);
    g.yfov = 1.2f;
    return g;
}

void expectUniformRadiance(const Image& image, glm::dvec3 expected) {
    ASSERT_TRUE(allFinite(image));
    PixelStatistics s = pixelStatistics(image);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(s.mean[c], expected[c], 5.0 * s.standardError[c] + 1e-6) << "channel " << c;
    }
}

}  // namespace vkdr::test
