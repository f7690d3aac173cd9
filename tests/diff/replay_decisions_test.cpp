// The adjoint pass replays the primal pass's paths and must take every decision the
// primal pass took: the same free flights, light samples, scattering directions and
// Russian roulette, in derivative mode too. The replay starts each path with the L the
// primal pass gathered and subtracts every contribution it passes, so where every
// decision is the same it ends with nothing left but rounding; a decision that diverges
// leaves (or over-subtracts) a whole contribution.
#include <cmath>

#include "bvh/bvh.h"
#include "gradient_scenes.h"
#include "render/renderer.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 16;
constexpr uint32_t kMaxDepth = 6;

// The foggy room with walls black in green and a box of smoke that does not scatter
// green: paths meet zero factors of both kinds and go on in derivative mode.
TestGltf roomWithZeroFactors() {
    TestGltf g = foggyRoom();
    g.materials[0] = diffuseMaterial("walls", glm::vec3(0.7f, 0.0f, 0.5f));
    g.materials.push_back(vkdrMediumMaterial("smoke", glm::vec3(0.2f), glm::vec3(2.0f, 0.0f, 1.0f), 0.5f));
    g.meshes.push_back(box(glm::vec3(-0.4f, -0.9f, -0.2f), glm::vec3(0.4f, -0.1f, 0.6f), 2));
    return g;
}

TEST_F(RenderTest, TheReplayTakesThePrimalPassesDecisions) {
    Scene scene = loadScene(roomWithZeroFactors().write(tempDir(), "zero_factors")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    // All paths in one pass, so that the primal and the adjoint pass use the same slots.
    Renderer renderer(testContext(), scene, bvh, {.width = kSide, .height = kSide, .spp = 8, .maxDepth = kMaxDepth, .seed = 5});
    renderer.enableGradients(Image{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)}, LossKind::L2);
    ASSERT_EQ(renderer.width(), kSide);
    renderer.loss();  // renders the paths exactly as the gradient pass's primal pass does
    const std::vector<glm::vec4> gathered = renderer.pathRadiance();
    renderer.renderWithGradients();
    const std::vector<glm::vec4> left = renderer.pathRadiance();

    // A path gathers at most 2 (maxDepth + 1) non-negative contributions; adding them to
    // a compensated sum (shaders/lib/compensated_sum.glsl) and subtracting them again
    // leaves at most about 2^-47 L per operation, under 1e-12 L in all (in plain floats it
    // would be about 1e-7 L, and a replayed contribution one ulp off from the primal
    // pass's would leave as much). A diverging decision leaves a whole contribution.
    constexpr float kRounding = 1e-12f;
    const int paths = kSide * kSide * 8;
    int litPaths = 0, diverged = 0;
    for (size_t slot = 0; slot < size_t(paths); ++slot) {
        litPaths += glm::any(glm::greaterThan(glm::vec3(gathered[slot]), glm::vec3(0.0f)));
        for (int c = 0; c < 3; ++c) {
            if (!(std::abs(left[slot][c]) <= kRounding * gathered[slot][c])) {
                if (++diverged <= 5) {
                    ADD_FAILURE() << "path " << slot << " channel " << c << ": gathered " << gathered[slot][c]
                                  << ", the replay left " << left[slot][c];
                }
            }
        }
    }
    EXPECT_EQ(diverged, 0);
    EXPECT_GT(litPaths, paths / 2);  // most paths reach the lamp in some channel
}

}  // namespace
}  // namespace vkdr::test
