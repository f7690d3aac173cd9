// A small inverse problem end to end: the Cornell box in an absorbing fog, sigma_a
// recovered from a rendered target by 60 iterations of Adam through the adjoint pass,
// at 32x32 pixels, 16 samples per iteration and direct lighting only, so that it runs
// in under a minute on lavapipe.
//
// Where Adam ends is no mean of independent samples, so its error has no standard
// error of its own; it is bounded by what moves the minimum and what moves the
// optimiser around it, both measured here from gradients over seeds at the true value.
// The target's own noise moves the minimum to sigma* = sigma - G / H, where G is the
// mean gradient at the true value and H the loss's curvature there (the gradient's
// change over +-50 %, where the loss is close to quadratic). Each iteration's gradient
// is noisy with standard deviation s, so one gradient's zero lies s / H from sigma*.
// Adam steps along its first moment, an exponential average of the gradients with
// beta1 = 0.9, whose variance is (1 - beta1) / (1 + beta1) = 1/19 of one gradient's;
// at the end its steps are at most the learning rate decayed to 5 % (5e-4, small
// against the rest). So the bound is 5 (one comparison) times s / (H sqrt(19)) and
// sigma*'s own standard error, added in quadrature; the test requires H to be known to
// a fifth or better.
#include <cmath>

#include "bvh/bvh.h"
#include "core/sample_statistics.h"
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

    const float recovered = getParameter(scene, "media/fog/sigma_a")[0];

    constexpr uint32_t kSeeds = 8;
    constexpr float kStep = 0.025f;
    auto gradientsAt = [&](float sigma, uint32_t seeds) {
        applyAssignment(scene, "media/fog/sigma_a=" + std::to_string(sigma));
        std::vector<double> g;
        for (uint32_t seed = 0; seed < seeds; ++seed) {
            g.push_back(lossGradient.evaluate(scene, seed).parameters[0].gradient[0]);
        }
        return g;
    };
    const std::vector<double> atTruth = gradientsAt(0.05f, 2 * kSeeds);
    const std::vector<double> above = gradientsAt(0.05f + kStep, kSeeds), below = gradientsAt(0.05f - kStep, kSeeds);
    std::vector<double> curvatures;
    for (uint32_t s = 0; s < kSeeds; ++s) {
        curvatures.push_back((above[s] - below[s]) / (2.0 * kStep));
    }
    const MeanAndError gradient = meanAndError(atTruth), curvature = meanAndError(curvatures);
    ASSERT_GT(curvature.mean, 5.0 * curvature.error) << "the loss is not convex in sigma_a here";
    const double perIteration = gradient.error * std::sqrt(double(atTruth.size())) / curvature.mean;
    const double firstMoment = perIteration / std::sqrt(19.0);
    const double minimum = 0.05 - gradient.mean / curvature.mean;
    const double minimumError = gradient.error / curvature.mean;
    EXPECT_NEAR(recovered, minimum, 5.0 * std::hypot(firstMoment, minimumError))
        << "the minimum " << minimum << " +- " << minimumError << ", Adam's first moment's zero +- " << firstMoment;
}

}  // namespace
}  // namespace vkdr::test
