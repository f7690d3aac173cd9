// render() reports its progress as it goes, within a pass as well as between passes: a
// render that fits in one pass (most renders on a CPU device) would otherwise say
// nothing until it ends.
#include <algorithm>

#include "render_test_support.h"
#include "bvh/bvh.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

class RenderProgressTest : public RenderTest {};

// Scattering smoke in a box of glowing walls, seen from inside: paths take many segments.
std::filesystem::path smokeInGlowingBox(const std::filesystem::path& dir) {
    TestGltf g;
    g.materials = {emissiveMaterial("walls", glm::vec3(1.0f), true),
                   vkdrMediumMaterial("smoke", glm::vec3(0.1f), glm::vec3(3.0f), 0.0f)};
    g.materials[0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.6, 0.6, 0.6, 1.0};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), box(glm::vec3(-0.8f), glm::vec3(0.8f, 0.8f, 0.9f), 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
    return g.write(dir, "scene");
}

std::vector<double> progressOfRender(const Scene& scene, const RenderSettings& settings) {
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Renderer renderer(testContext(), scene, bvh, settings);
    std::vector<double> reports;
    renderer.render([&](double fraction) { reports.push_back(fraction); });
    return reports;
}

void expectRisingToOne(const std::vector<double>& reports) {
    ASSERT_FALSE(reports.empty());
    for (size_t i = 0; i < reports.size(); ++i) {
        EXPECT_GE(reports[i], 0.0) << "report " << i;
        EXPECT_LE(reports[i], 1.0) << "report " << i;
        if (i > 0) {
            EXPECT_GE(reports[i], reports[i - 1]) << "report " << i;
        }
    }
    EXPECT_EQ(reports.back(), 1.0);
}

TEST_F(RenderProgressTest, ARenderOfOnePassReportsProgressBeforeItEnds) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    const std::vector<double> reports = progressOfRender(scene, {.width = 16, .height = 12, .spp = 4, .maxDepth = 6});
    expectRisingToOne(reports);
    ASSERT_GE(reports.size(), 2u);
    EXPECT_LT(reports.front(), 1.0);
}

TEST_F(RenderProgressTest, ARenderOfManyPassesReportsEachPassAndWithinIt) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    // A pass of every pixel's one sample: a pass a sample.
    const uint32_t passes = 4;
    const RenderSettings settings{.width = 16, .height = 12, .spp = passes, .maxDepth = 6, .pathsPerPass = 16 * 12};
    const std::vector<double> reports = progressOfRender(scene, settings);
    expectRisingToOne(reports);
    for (uint32_t pass = 1; pass <= passes; ++pass) {
        const double end = double(pass) / passes;
        EXPECT_TRUE(std::find(reports.begin(), reports.end(), end) != reports.end()) << "pass " << pass;
    }
    EXPECT_GT(reports.size(), 2 * size_t(passes));
}

}  // namespace
}  // namespace vkdr::test
