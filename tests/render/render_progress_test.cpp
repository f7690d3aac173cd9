// render() and the gradient evaluations report their progress as they go, within a
// pass as well as between passes: a job that fits in one pass (most on a CPU device)
// would otherwise say nothing until it ends.
#include <algorithm>
#include <set>

#include "render_test_support.h"
#include "bvh/bvh.h"
#include "diff/gradient_check.h"
#include "diff/rendered_loss_gradient.h"
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

size_t distinctReportsInside(const std::vector<double>& reports) {
    std::set<double> inside;
    for (double fraction : reports) {
        if (fraction > 0.0 && fraction < 1.0) inside.insert(fraction);
    }
    return inside.size();
}

// Each of the three estimators of renderWithGradients (docs/gradients.md) renders,
// back-propagates and perhaps replays in several passes; between passes alone they
// would report at most passes - 1 distinct fractions below 1.
TEST_F(RenderProgressTest, AGradientEvaluationReportsProgressWithinItsPasses) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    const Image target{16, 12, std::vector<float>(16 * 12 * 3, 0.5f)};
    struct Case {
        const char* estimator;
        RenderSettings settings;
        size_t mostPasses;
    };
    const Case cases[] = {
        {"both halves in one pass", {.width = 16, .height = 12, .spp = 4, .maxDepth = 6}, 2},
        {"one sample, replayed", {.width = 16, .height = 12, .spp = 1, .maxDepth = 6}, 3},
        // Halves of 2 samples in passes of one sample: rendered, back-propagated and
        // perhaps replayed, a pass each.
        {"halves in passes", {.width = 16, .height = 12, .spp = 4, .maxDepth = 6, .pathsPerPass = 16 * 12}, 10},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.estimator);
        Renderer renderer(testContext(), scene, bvh, c.settings);
        renderer.enableGradients(target, LossKind::L2, DerivativeTargets::of({ParameterKind::SigmaS}));
        std::vector<double> reports;
        renderer.renderWithGradients([&](double fraction) { reports.push_back(fraction); });
        expectRisingToOne(reports);
        EXPECT_GT(distinctReportsInside(reports), c.mostPasses - 1);
    }
}

// Views are equal shares of an evaluation, whether a view has a renderer of its own or
// shares one with views of its size.
TEST_F(RenderProgressTest, AGradientOfSeveralViewsReportsEachViewsShare) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    const Image small{16, 12, std::vector<float>(16 * 12 * 3, 0.5f)};
    const Image large{20, 15, std::vector<float>(20 * 15 * 3, 0.5f)};
    const std::vector<TargetView> views = {{"", small}, {"", large}, {"", small}};
    RenderedLossGradient lossGradient(testContext(), scene, views, {"media/smoke/sigma_s"},
                                      {.spp = 4, .maxDepth = 6}, LossKind::L2);
    std::vector<double> reports;
    lossGradient.reportProgress([&](double fraction) { reports.push_back(fraction); });
    lossGradient.evaluate(scene, 7);
    expectRisingToOne(reports);
    for (double viewEnd : {1.0 / 3.0, 2.0 / 3.0}) {
        EXPECT_TRUE(std::find(reports.begin(), reports.end(), viewEnd) != reports.end()) << viewEnd;
    }
    EXPECT_TRUE(std::any_of(reports.begin(), reports.end(), [](double f) { return f > 0.0 && f < 1.0 / 3.0; }));
}

// A gradient check's adjoint evaluations are its longest steps: it reports within them,
// and leaves the evaluation's own reports unset after it.
TEST_F(RenderProgressTest, AGradientCheckReportsWithinItsAdjointEvaluations) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    const std::vector<TargetView> views = {{"", Image{8, 6, std::vector<float>(8 * 6 * 3, 0.5f)}}};
    RenderedLossGradient lossGradient(testContext(), scene, views, {"media/smoke/g"}, {.spp = 4, .maxDepth = 4},
                                      LossKind::L2);
    std::vector<double> reports;
    checkGradients(lossGradient, scene, {"media/smoke/g"}, 2, 1, [&](double fraction) { reports.push_back(fraction); });
    expectRisingToOne(reports);
    // Two seeds of one value: four steps, the first the first seed's adjoint evaluation.
    EXPECT_TRUE(std::any_of(reports.begin(), reports.end(), [](double f) { return f > 0.0 && f < 0.25; }));
    size_t before = reports.size();
    lossGradient.evaluate(scene, 3);
    EXPECT_EQ(reports.size(), before);
}

// grad --check hands the check its own evaluation at the first seed: the check takes
// it in place of evaluating that seed again, and counts it as its first step done.
TEST_F(RenderProgressTest, AGradientCheckTakesTheEvaluationItIsGivenAtItsFirstSeed) {
    Scene scene = loadScene(smokeInGlowingBox(tempDir())).scene;
    const std::vector<TargetView> views = {{"", Image{8, 6, std::vector<float>(8 * 6 * 3, 0.5f)}}};
    RenderedLossGradient lossGradient(testContext(), scene, views, {"media/smoke/g"}, {.spp = 4, .maxDepth = 4},
                                      LossKind::L2);
    GradientResult given = lossGradient.evaluate(scene, 1);
    const double atSecondSeed = lossGradient.evaluate(scene, 2).parameters[0].gradient[0];
    given.parameters[0].gradient[0] = 1000.0;
    std::vector<double> reports;
    const std::vector<GradientCheckRow> rows = checkGradients(
        lossGradient, scene, {"media/smoke/g"}, 2, 1, [&](double fraction) { reports.push_back(fraction); }, &given);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_DOUBLE_EQ(rows[0].adjoint, (1000.0 + atSecondSeed) / 2.0);
    expectRisingToOne(reports);
    // Two seeds of one value: four steps, the first done before the check began.
    EXPECT_GE(reports.front(), 0.25);
}

}  // namespace
}  // namespace vkdr::test
