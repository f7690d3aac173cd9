// In a furnace filled with conservative media (sigma_a = 0), the image is Le / (1 - rho)
// whatever their sigma_s and g, so those gradients are zero: the adjoint's mean over
// seeds must be within four standard errors of 0. sigma_a, which does change the image,
// must have a gradient many standard errors from 0, so the test sees real gradients.
// Long free flights make single gradients heavy-tailed, so many cheap seeds (rather
// than a few expensive ones) give a standard error that can be trusted.
#include <cmath>

#include "core/sample_statistics.h"
#include "diff/rendered_loss_gradient.h"
#include "furnace_scene.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
constexpr int kSeeds = 96;

class FurnaceGradientTest : public RenderTest {};

TEST_F(FurnaceGradientTest, ScatteringAndAnisotropyDoNotChangeTheImage) {
    TestGltf g = furnace(glm::vec3(0.5f));
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.0, 0.0, 0.0}}, {"sigma_s", {0.5, 1.0, 2.0}}, {"g", 0.6}};
    // Two conservative boxes side by side: shadow rays from one through the other cross
    // three media, more than the shadow stage records, so it traces them a second time.
    g.materials.push_back(vkdrMediumMaterial("left", glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.5f), -0.4f));
    g.materials.push_back(vkdrMediumMaterial("right", glm::vec3(0.0f), glm::vec3(1.5f), 0.3f));
    g.meshes.push_back(box(glm::vec3(-0.8f, -0.5f, 0.2f), glm::vec3(-0.2f, 0.5f, 0.8f), 1));
    g.meshes.push_back(box(glm::vec3(0.2f, -0.5f, 0.2f), glm::vec3(0.8f, 0.5f, 0.8f), 2));
    Scene scene = loadScene(g.write(tempDir(), "furnace")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    const std::vector<std::string> names = {"media/fog/sigma_s", "media/fog/g",   "media/left/sigma_s",
                                            "media/right/g",     "media/fog/sigma_a"};
    // Deep enough that truncation, which does depend on sigma_s, is far below the noise.
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, names, {.spp = 8, .maxDepth = 400}, LossKind::L2);
    std::vector<std::vector<std::vector<double>>> samples(names.size(), std::vector<std::vector<double>>(3));
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        GradientResult r = lg.evaluate(scene, seed);
        for (size_t p = 0; p < names.size(); ++p) {
            for (size_t c = 0; c < r.parameters[p].gradient.size(); ++c) {
                samples[p][c].push_back(r.parameters[p].gradient[c]);
            }
        }
    }
    for (size_t p = 0; p < names.size(); ++p) {
        for (size_t c = 0; c < samples[p].size() && !samples[p][c].empty(); ++c) {
            MeanAndError gradient = meanAndError(samples[p][c]);
            ASSERT_GT(gradient.error, 0.0) << names[p] << "[" << c << "]";
            if (names[p] == "media/fog/sigma_a") {
                EXPECT_LT(gradient.mean, -10.0 * gradient.error) << names[p] << "[" << c << "]";
            } else {
                EXPECT_NEAR(gradient.mean, 0.0, 4.0 * gradient.error)
                    << names[p] << "[" << c << "]: standard error " << gradient.error;
            }
        }
    }
}

}  // namespace
}  // namespace vkdr::test
