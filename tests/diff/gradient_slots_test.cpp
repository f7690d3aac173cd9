// Reading a named parameter's gradient out of the adjoint pass's accumulators, for every
// kind of parameter, without a GPU: each accumulator float holds its own index.
#include <numeric>

#include <gtest/gtest.h>

#include "device_types.h"
#include "diff/gradient_slots.h"
#include "expect_error.h"

namespace vkdr::test {
namespace {

Scene sceneWithTwoOfEverything() {
    Scene scene;
    scene.media = {{"fog", glm::vec3(0.1f), glm::vec3(0.2f), 0.3f}, {"smoke", glm::vec3(0.5f), glm::vec3(1.5f), 0.6f}};
    scene.textures = {{"first", 1, 1, {glm::vec4(0.5f)}}, {"checker", 2, 1, {glm::vec4(0.1f), glm::vec4(0.4f)}}};
    Material white, light;
    white.name = "white";
    light.name = "light";
    light.emission = glm::vec3(1.0f);
    light.emitter = true;
    light.baseColorTexture = 1;
    scene.materials = {white, light};
    PunctualLight bulb, sun;
    bulb.name = "bulb";
    sun.name = "sun";
    scene.punctualLights = {bulb, sun};
    return scene;
}

std::vector<float> indices(size_t count) {
    std::vector<float> values(count);
    std::iota(values.begin(), values.end(), 0.0f);
    return values;
}

std::vector<double> gradientOf(const std::string& name) {
    const Scene scene = sceneWithTwoOfEverything();
    const uint32_t color = gpu::kColorGradientStride;
    const SceneGradients gradients{indices(2 * gpu::kMediumGradientStride), indices(2 * color), indices(2 * color),
                                   indices(2 * color), indices(3 * color)};
    return gatherGradient(resolveGradientSlots(scene, {name}).at(0), gradients);
}

std::vector<double> sequence(double first, size_t count) {
    std::vector<double> values(count);
    std::iota(values.begin(), values.end(), first);
    return values;
}

TEST(GradientSlot, ReadsEveryKindFromItsAccumulator) {
    const double smoke = gpu::kMediumGradientStride;
    EXPECT_EQ(gradientOf("media/smoke/sigma_a"), sequence(smoke + gpu::kMediumGradientSigmaA, 3));
    EXPECT_EQ(gradientOf("media/smoke/sigma_s"), sequence(smoke + gpu::kMediumGradientSigmaS, 3));
    EXPECT_EQ(gradientOf("media/fog/g"), sequence(gpu::kMediumGradientG, 1));
    const double color = gpu::kColorGradientStride;
    EXPECT_EQ(gradientOf("materials/light/base_color"), sequence(color, 3));
    EXPECT_EQ(gradientOf("lights/light/emission"), sequence(color, 3));
    EXPECT_EQ(gradientOf("lights/sun/intensity"), sequence(color, 3));
    // The checker's two texels follow the first texture's one.
    EXPECT_EQ(gradientOf("materials/light/base_color_texture"), sequence(color, 6));
}

TEST(GradientSlot, KeepsTheKindForTheAdjointsDerivativeTargets) {
    const Scene scene = sceneWithTwoOfEverything();
    std::vector<GradientSlot> slots = resolveGradientSlots(scene, {"media/fog/sigma_s", "lights/light/emission"});
    EXPECT_EQ(slots[0].kind, ParameterKind::SigmaS);
    EXPECT_EQ(slots[1].kind, ParameterKind::Emission);
    expectErrorMentioning([&] { resolveGradientSlots(scene, {"media/haze/g"}); },
                          {"unknown parameter 'media/haze/g'", "media/fog/g"});
    expectErrorMentioning([&] { resolveGradientSlots(scene, {"media/fog/g", "lights/light/emission", "media/fog/g"}); },
                          {"parameter 'media/fog/g' is given twice"});
}

// Two names of one texture (two materials share it) would each get the whole gradient,
// and a fit would step the texels once for each.
TEST(GradientSlot, RefusesTwoNamesOfTheSameValues) {
    Scene scene = sceneWithTwoOfEverything();
    scene.materials[0].baseColorTexture = 1;
    expectErrorMentioning(
        [&] { resolveGradientSlots(scene, {"materials/white/base_color_texture", "materials/light/base_color_texture"}); },
        {"'materials/white/base_color_texture' and 'materials/light/base_color_texture' name the same values"});
    scene.materials[0].baseColorTexture = 0;
    EXPECT_EQ(resolveGradientSlots(scene, {"materials/white/base_color_texture", "materials/light/base_color_texture"})
                  .size(),
              2u);
    // A medium's coefficients share an accumulator, not values.
    EXPECT_EQ(resolveGradientSlots(scene, {"media/fog/sigma_a", "media/fog/sigma_s", "media/fog/g"}).size(), 3u);
}


// A grid of no active voxels holds no values: naming it would give an empty gradient and
// a fit of nothing.
TEST(GradientSlot, RefusesAGridOfNoActiveVoxels) {
    Scene scene = sceneWithTwoOfEverything();
    SceneDensityGrid empty;
    empty.file = "/scenes/unfinished.vdb";
    empty.grid.name = "density";
    SceneDensityGrid smoke = empty;
    smoke.file = "/scenes/smoke.vdb";
    smoke.grid.size = glm::ivec3(2, 1, 1);
    smoke.grid.values = {0.5f, 1.0f};
    scene.densityGrids = {smoke, empty};
    scene.media[0].densityGrid = 0;
    scene.media[1].densityGrid = 1;
    EXPECT_EQ(resolveGradientSlots(scene, {"media/fog/density"}).at(0).valueCount(), 2u);
    expectErrorMentioning([&] { resolveGradientSlots(scene, {"media/smoke/density"}); },
                          {"parameter media/smoke/density", "'density' in unfinished.vdb has no active voxels"});
}

}  // namespace
}  // namespace vkdr::test
