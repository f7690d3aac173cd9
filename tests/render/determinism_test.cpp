// The same scene, seed and device give the same image bit for bit, whatever order the
// paths finish in; another seed gives another image. New parameter values given to a
// renderer render as a renderer made for them does. Gradients have the same bits
// however their lanes add them, and however the paths are split into passes.
#include "render_test_support.h"
#include "bvh/bvh.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

class DeterminismTest : public RenderTest {};

// A block of smoke in a box of glowing walls, seen from inside the box.
TestGltf smokeInGlowingBox(glm::vec3 sigmaS) {
    TestGltf g;
    g.materials = {emissiveMaterial("walls", glm::vec3(1.0f, 0.8f, 0.6f), true),
                   vkdrMediumMaterial("smoke", glm::vec3(0.1f), sigmaS, 0.4f)};
    g.materials[0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.6, 0.6, 0.6, 1.0};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), box(glm::vec3(-0.5f), glm::vec3(0.5f, 0.5f, 0.9f), 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
    return g;
}

TEST_F(DeterminismTest, SameSeedSameBitsOtherSeedOtherImage) {
    auto file = smokeInGlowingBox(glm::vec3(2.0f)).write(tempDir(), "scene");
    // A small pass size makes the render span several passes and queue orders.
    RenderSettings settings{.width = 16, .height = 12, .spp = 8, .maxDepth = 6, .seed = 7, .pathsPerPass = 500};
    Image a = renderFile(file, settings);
    Image b = renderFile(file, settings);
    ASSERT_TRUE(allFinite(a));
    EXPECT_EQ(a.rgb, b.rgb);
    settings.seed = 8;
    Image c = renderFile(file, settings);
    EXPECT_NE(a.rgb, c.rgb);
}

// However the paths are split into passes (one pass; several of whole pixels' samples;
// passes that split pixels' samples, and split them unevenly around the gradient's two
// halves), the image, the loss and every gradient have the same bits: the film adds
// each pixel's samples one by one in sample order, and the gradients are fixed-point sums.
TEST_F(DeterminismTest, TheBitsDoNotDependOnHowPathsAreSplitIntoPasses) {
    Scene scene = loadScene(smokeInGlowingBox(glm::vec3(2.0f)).write(tempDir(), "scene")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings{.width = 16, .height = 12, .spp = 8, .maxDepth = 6, .seed = 7};
    const Image target = Renderer(testContext(), scene, bvh, settings).render();
    scene.media[0].sigma_s *= 0.5f;
    auto evaluate = [&](uint32_t pathsPerPass) {
        RenderSettings split = settings;
        split.pathsPerPass = pathsPerPass;
        Renderer renderer(testContext(), scene, bvh, split);
        renderer.enableGradients(target, LossKind::L2, DerivativeTargets{});
        return std::make_pair(renderer.render(), renderer.renderWithGradients());
    };
    const auto [image, expected] = evaluate(0);
    ASSERT_TRUE(allFinite(image));
    for (uint32_t pathsPerPass : {16u * 12u * 2u, 500u, 37u}) {
        const auto [splitImage, evaluation] = evaluate(pathsPerPass);
        EXPECT_EQ(splitImage.rgb, image.rgb) << pathsPerPass << " paths per pass";
        EXPECT_EQ(evaluation.image.rgb, expected.image.rgb) << pathsPerPass << " paths per pass";
        EXPECT_EQ(evaluation.loss, expected.loss) << pathsPerPass << " paths per pass";
#define VKDR_EXPECT_SAME_GRADIENTS(name, field, ...) \
    EXPECT_EQ(evaluation.gradients.field, expected.gradients.field) << #field << ", " << pathsPerPass << " paths per pass";
        VKDR_GRADIENT_ACCUMULATORS(VKDR_EXPECT_SAME_GRADIENTS)
#undef VKDR_EXPECT_SAME_GRADIENTS
    }
}

// setParameters keeps the emitter distribution when no emission changed and rebuilds it
// when one did, here from one emitter to two: a stale distribution would sample other
// lights (or miss the new one) and give other bits. The medium starts without
// scattering, so the stages are compiled without equiangular sampling until it scatters.
TEST_F(DeterminismTest, NewParameterValuesRenderAsAFreshRendererDoes) {
    TestGltf g;
    g.materials = {emissiveMaterial("walls", glm::vec3(1.0f, 0.8f, 0.6f), true), diffuseMaterial("block", glm::vec3(0.5f)),
                   vkdrMediumMaterial("smoke", glm::vec3(0.1f), glm::vec3(0.0f), 0.4f)};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), box(glm::vec3(-0.3f), glm::vec3(0.3f), 1),
                box(glm::vec3(-0.5f, 0.4f, -0.5f), glm::vec3(0.5f, 0.9f, 0.9f), 2)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
    Scene scene = loadScene(g.write(tempDir(), "scene")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings{.width = 16, .height = 12, .spp = 4, .maxDepth = 6, .seed = 3};
    Renderer reused(testContext(), scene, bvh, settings);
    reused.render();

    auto expectSameAsFresh = [&](const Scene& changed) {
        reused.setParameters(changed);
        Image image = reused.render();
        ASSERT_TRUE(allFinite(image));
        EXPECT_EQ(image.rgb, Renderer(testContext(), changed, bvh, settings).render().rgb);
    };
    scene.media[0].sigma_s = glm::vec3(0.5f, 1.0f, 1.5f);
    scene.materials[1].baseColor = glm::vec3(0.2f, 0.4f, 0.6f);
    expectSameAsFresh(scene);
    scene.materials[1].emission = glm::vec3(4.0f);
    expectSameAsFresh(scene);
    scene.materials[0].emission = glm::vec3(0.1f);
    expectSameAsFresh(scene);
}

// A fit that makes a medium scatter where none did recompiles the adjoint stages with
// the primal ones (equiangular sampling is compiled in only then): the gradients are a
// fresh renderer's, bit for bit.
TEST_F(DeterminismTest, GradientsAfterAMediumStartsToScatterAreAFreshRenderersGradients) {
    Scene scene = loadScene(smokeInGlowingBox(glm::vec3(0.0f)).write(tempDir(), "scene")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    RenderSettings settings{.width = 12, .height = 8, .spp = 4, .maxDepth = 4, .seed = 3};
    const DerivativeTargets targets = DerivativeTargets::of({ParameterKind::SigmaA, ParameterKind::G});
    Renderer reused(testContext(), scene, bvh, settings);
    const Image target = reused.render();
    reused.enableGradients(target, LossKind::L2, targets);
    reused.renderWithGradients();

    scene.media[0].sigma_s = glm::vec3(1.5f, 1.0f, 0.5f);
    reused.setParameters(scene);
    const GradientEvaluation evaluation = reused.renderWithGradients();
    Renderer fresh(testContext(), scene, bvh, settings);
    fresh.enableGradients(target, LossKind::L2, targets);
    const GradientEvaluation expected = fresh.renderWithGradients();
    EXPECT_EQ(evaluation.image.rgb, expected.image.rgb);
    EXPECT_EQ(evaluation.gradients.media, expected.gradients.media);
    EXPECT_NE(evaluation.gradients.media[gpu::kMediumGradientG], 0.0f);  // the medium scatters
}

// A medium that does not scatter is passed through by a render and sampled by a gradient
// pass that wants sigma_s's gradient (medium_sample.comp): a render after such a pass, or
// on a renderer set up for one, is the plain render, bit for bit.
TEST_F(DeterminismTest, ARenderDoesNotDependOnWhatTheRendererDifferentiates) {
    TestGltf g;
    g.materials = {emissiveMaterial("walls", glm::vec3(1.0f, 0.8f, 0.6f), true),
                   vkdrMediumMaterial("ink", glm::vec3(0.7f, 0.3f, 0.1f), glm::vec3(0.0f), 0.0f)};
    g.materials[0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.6, 0.6, 0.6, 1.0};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0), box(glm::vec3(-0.5f), glm::vec3(0.5f, 0.5f, 0.9f), 1)};
    g.cameraPosition = glm::vec3(0.0f, 0.0f, -0.95f);
    LoadedScene loaded = loadScene(g.write(tempDir(), "scene"));
    Bvh bvh = buildBvh(loaded.scene.positions, loaded.scene.triangles);
    RenderSettings settings{.width = 12, .height = 8, .spp = 4, .maxDepth = 4, .seed = 3};
    Renderer plain(testContext(), loaded.scene, bvh, settings);
    const Image expected = plain.render();

    Renderer differentiating(testContext(), loaded.scene, bvh, settings);
    differentiating.enableGradients(expected, LossKind::L2,
                                    DerivativeTargets::of({ParameterKind::SigmaS, ParameterKind::BaseColor}));
    EXPECT_EQ(differentiating.render().rgb, expected.rgb);
    const GradientEvaluation evaluation = differentiating.renderWithGradients();
    EXPECT_EQ(differentiating.render().rgb, expected.rgb);
    // The gradient pass sampled the ink: a gradient pass that does not want sigma_s's
    // gradient, with the same sample points, passes through it and gives another image.
    Renderer notScattering(testContext(), loaded.scene, bvh, settings);
    notScattering.enableGradients(expected, LossKind::L2, DerivativeTargets::of({ParameterKind::BaseColor}));
    EXPECT_NE(evaluation.image.rgb, notScattering.renderWithGradients().image.rgb);
}

}  // namespace
}  // namespace vkdr::test
