// A small inverse problem end to end: the Cornell box in an absorbing fog, sigma_a
// recovered from a rendered target by 60 iterations of Adam through the adjoint pass,
// at 32x32 pixels, 16 samples per iteration and direct lighting only, so that it runs
// in under a minute on lavapipe.
//
// The target's own noise moves the minimum: at 256 spp the image's mean varies by
// about 3 % between seeds, with a long bright tail, so a typical target is darker than
// its expectation and the fits came out 2-11 % high. At 4096 spp it varies by 0.6 %.
// With that target, optimisation seeds 1000 to 4000 recovered +0.0 %, -2.8 %, +2.0 %
// and -1.9 %: a spread of about 2 %, of which 8 % is four times.
#include <cmath>

#include "bvh/bvh.h"
#include "diff/rendered_loss_gradient.h"
#include "optimize/optimize_loop.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

class RecoveryTest : public RenderTest {};

TEST_F(RecoveryTest, AdamRecoversTheAbsorptionOfAFog) {
    Scene scene = loadScene(std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_fog.gltf").scene;
    applyAssignment(scene, "media/fog/sigma_s=0");
    applyAssignment(scene, "media/fog/sigma_a=0.05");
    RenderSettings settings{.width = 32, .height = 32, .spp = 4096, .maxDepth = 1, .seed = 0x80000000u};
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Image target = Renderer(testContext(), scene, bvh, settings).render();

    applyAssignment(scene, "media/fog/sigma_a=0.1");
    const std::vector<std::string> parameters = {"media/fog/sigma_a"};
    RenderedLossGradient lossGradient(testContext(), scene, {{"", target}}, parameters,
                                      {.spp = 16, .maxDepth = 1}, LossKind::L2);
    OptimizeOptions options{.parameters = parameters, .optimizer = OptimizerKind::Adam, .learningRate = 0.01,
                            .learningRateDecay = 0.05, .iterations = 60, .seed = 1000};
    optimize(lossGradient, scene, options);

    for (float recovered : getParameter(scene, "media/fog/sigma_a")) {
        EXPECT_NEAR(recovered, 0.05f, 0.08f * 0.05f);
    }
}

}  // namespace
}  // namespace vkdr::test
