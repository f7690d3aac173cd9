// Direct light from an area light at oblique angles, against Lambert's closed form for
// the irradiance of a polygon of constant radiance: the Cornell box's side wall, lit
// from the ceiling lamp at grazing angles, where next-event estimation and BSDF sampling
// share the work through MIS; a floor under a lamp vastly larger than it; and a floor
// under a strip lamp whose triangles are slivers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <vector>

#include "bvh/bvh.h"
#include "furnace_scene.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

// Lambert's formula: the irradiance at p (normal n) from a convex polygon of radiance 1,
// 1/2 sum over its edges of the angle the edge subtends times the cosine of the edge
// plane's normal with n.
double polygonIrradiance(const std::vector<glm::dvec3>& polygon, glm::dvec3 p, glm::dvec3 n) {
    double sum = 0.0;
    for (size_t i = 0; i < polygon.size(); ++i) {
        glm::dvec3 a = glm::normalize(polygon[i] - p);
        glm::dvec3 b = glm::normalize(polygon[(i + 1) % polygon.size()] - p);
        glm::dvec3 c = glm::cross(a, b);
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, c) / glm::length(c);
    }
    return std::abs(sum) / 2.0;
}

// The corners of the lamp: the emissive triangles' vertices, in order around their
// bounding rectangle (the lamp is an axis-aligned quad in the plane y = const).
std::vector<glm::dvec3> lampPolygon(const Scene& scene, glm::dvec3* radiance) {
    glm::dvec3 low(1e30), high(-1e30);
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const Material& material = scene.materials[scene.triangleMaterial[t]];
        if (material.isEmissive()) {
            *radiance = glm::dvec3(material.emission);
            for (int c = 0; c < 3; ++c) {
                low = glm::min(low, glm::dvec3(scene.positions[scene.triangles[t][c]]));
                high = glm::max(high, glm::dvec3(scene.positions[scene.triangles[t][c]]));
            }
        }
    }
    return {{low.x, low.y, low.z}, {high.x, low.y, low.z}, {high.x, low.y, high.z}, {low.x, low.y, high.z}};
}

TEST_F(RenderTest, AWallLitAtGrazingAnglesMatchesLambertsFormula) {
    const LoadedScene loaded = loadScene(std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_box.gltf");
    const Scene& scene = loaded.scene;
    glm::dvec3 radiance(0.0);
    const std::vector<glm::dvec3> lamp = lampPolygon(scene, &radiance);
    // The green wall: the plane x = 0 of the box, facing +x.
    uint32_t green = 0;
    while (scene.materials[green].name != "green") {
        ++green;
    }
    const glm::dvec3 albedo(scene.materials[green].baseColor);
    const double wallX = scene.positions[scene.triangles[std::distance(
        scene.triangleMaterial.begin(),
        std::find(scene.triangleMaterial.begin(), scene.triangleMaterial.end(), green))][0]].x;
    const double ceiling = lamp[0].y;

    constexpr int kSide = 64;
    constexpr uint32_t kSpp = 512;
    std::vector<Image> renders;
    for (uint32_t seed : {1u, 2u}) {
        renders.push_back(renderFile(std::filesystem::path(VKDR_TEST_SCENES_DIR) / "cornell_box.gltf",
                                     {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 1, .seed = seed}));
    }

    // Pixels whose whole footprint lies on the wall's upper part, above the blocks, so
    // that nothing stands between it and the lamp; the expectation averages the closed
    // form over an 8x8 grid in the pixel (the box filter).
    const Camera& camera = scene.cameras[0];
    const glm::dvec3 origin(camera.cameraToWorld[3]);
    const double tanHalf = std::tan(0.5 * camera.yfov);
    glm::dvec3 expectedSum(0.0), renderedSum(0.0), variance(0.0);
    int pixels = 0;
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            glm::dvec3 irradiance(0.0);
            bool onWall = true;
            for (int s = 0; s < 64 && onWall; ++s) {
                glm::dvec2 ndc = (glm::dvec2(x, y) + (glm::dvec2(s % 8, s / 8) + 0.5) / 8.0) / double(kSide) * 2.0 - 1.0;
                glm::dvec3 local(ndc.x * tanHalf, -ndc.y * tanHalf, -1.0);
                glm::dvec3 direction = glm::dmat3(camera.cameraToWorld) * local;
                double t = (wallX - origin.x) / direction.x;
                glm::dvec3 p = origin + t * direction;
                onWall = t > 0.0 && p.y > 0.7 * ceiling && p.y < 0.97 * ceiling && p.z > 0.05 * ceiling &&
                         p.z < 0.95 * ceiling;
                irradiance += polygonIrradiance(lamp, p, glm::dvec3(1.0, 0.0, 0.0)) / 64.0;
            }
            if (!onWall) {
                continue;
            }
            ++pixels;
            expectedSum += albedo * std::numbers::inv_pi * radiance * irradiance;
            for (int c = 0; c < 3; ++c) {
                const double a = renders[0].pixel(x, y)[c], b = renders[1].pixel(x, y)[c];
                renderedSum[c] += 0.5 * (a + b);
                variance[c] += 0.25 * (a - b) * (a - b);  // of the mean of the two renders
            }
        }
    }
    ASSERT_GT(pixels, 40);
    // The pixels are independent estimates; the variance of their sum comes from the two
    // seeds' differences. 5 standard errors, plus float rounding.
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(renderedSum[c], expectedSum[c], 5.0 * std::sqrt(variance[c]) + 1e-5 * expectedSum[c])
            << "channel " << c << " over " << pixels << " pixels";
    }
}

// A lamp 1e5 wide, 1 above a small floor: rays leave the floor by an offset that follows
// the floor's own coordinates, not the scene's extent, so they start below the lamp and
// the floor is lit as Lambert's formula says, almost as by an infinite plane.
TEST_F(RenderTest, AFloorUnderAVastLampMatchesLambertsFormula) {
    const glm::dvec3 le(1.0, 2.0, 3.0), albedo(0.5, 0.6, 0.7);
    constexpr float kLampHalfSize = 1.0e5f, kLampHeight = 1.0f;
    TestGltf scene;
    scene.materials = {diffuseMaterial("floor", glm::vec3(albedo)), emissiveMaterial("lamp", glm::vec3(le), false)};
    scene.meshes = {quadZ(0.0f, 0.0f, 1.0f, 0.0f, true, 0), quadZ(0.0f, 0.0f, kLampHalfSize, kLampHeight, false, 1)};
    scene.cameraPosition = glm::vec3(0.0f, 0.0f, 0.5f);
    scene.cameraLooksAlongPlusZ = false;
    scene.yfov = 0.5f;
    const double h = kLampHalfSize;
    const std::vector<glm::dvec3> lamp = {{-h, -h, kLampHeight}, {h, -h, kLampHeight}, {h, h, kLampHeight},
                                          {-h, h, kLampHeight}};
    // The camera sees the floor within 0.13 of its centre, where the irradiance differs
    // from the centre's by under 1e-10.
    const double irradiance = polygonIrradiance(lamp, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0));
    auto file = scene.write(tempDir(), "vast_lamp");
    expectUniformRadiance(renderFile(file, {.width = 16, .height = 16, .spp = 64, .maxDepth = 1}),
                          albedo * std::numbers::inv_pi * le * irradiance);
}

// A strip lamp 2 long and 2w wide, 1 above a floor, seen by a camera halfway between:
// each of its two triangles is a sliver (an angle of atan(w)), which the floor sees
// under about 1.4 w sr, on either side of the solid angle below which next-event
// estimation samples by area instead (kMinSphericalSamplingArea, 0.01 sr). The image's
// mean is the floor's radiance under Lambert's formula, averaged over the square of
// floor the camera sees.
class SliverLampTest : public RenderTest, public ::testing::WithParamInterface<float> {};

TEST_P(SliverLampTest, LightsAFloorAsLambertsFormulaSays) {
    const float halfWidth = GetParam();
    const glm::dvec3 le(1.0, 2.0, 3.0), albedo(0.5, 0.6, 0.7);
    constexpr float kLampHeight = 1.0f, kCameraHeight = 0.5f, kYfov = 0.5f;
    TestGltf scene;
    scene.materials = {diffuseMaterial("floor", glm::vec3(albedo)), emissiveMaterial("lamp", glm::vec3(le), false)};
    scene.meshes = {quadZ(0.0f, 0.0f, 1.0f, 0.0f, true, 0),
                    rectangleZ(glm::vec2(-1.0f, -halfWidth), glm::vec2(1.0f, halfWidth), kLampHeight, false, 1)};
    scene.cameraPosition = glm::vec3(0.0f, 0.0f, kCameraHeight);
    scene.cameraLooksAlongPlusZ = false;
    scene.yfov = kYfov;
    const double w = halfWidth;
    const std::vector<glm::dvec3> lamp = {{-1.0, -w, kLampHeight}, {1.0, -w, kLampHeight}, {1.0, w, kLampHeight},
                                          {-1.0, w, kLampHeight}};
    // The camera looks straight down, so its pixels cover the square |x|, |y| < s of the
    // floor evenly; the irradiance is smooth there and a 256 x 256 midpoint rule is
    // exact to far below the renders' noise.
    const double s = kCameraHeight * std::tan(0.5 * kYfov);
    constexpr int kGrid = 256;
    double meanIrradiance = 0.0;
    for (int i = 0; i < kGrid; ++i) {
        for (int j = 0; j < kGrid; ++j) {
            const glm::dvec3 p(s * ((2.0 * i + 1.0) / kGrid - 1.0), s * ((2.0 * j + 1.0) / kGrid - 1.0), 0.0);
            meanIrradiance += polygonIrradiance(lamp, p, glm::dvec3(0.0, 0.0, 1.0)) / (kGrid * kGrid);
        }
    }
    const glm::dvec3 expected = albedo * std::numbers::inv_pi * le * meanIrradiance;

    constexpr uint32_t kSide = 16;
    const auto file = scene.write(tempDir(), "sliver_lamp");
    std::vector<Image> renders;
    for (uint32_t seed : {1u, 2u}) {
        renders.push_back(renderFile(file, {.width = kSide, .height = kSide, .spp = 256, .maxDepth = 1, .seed = seed}));
    }
    // The pixels are independent estimates, and the two seeds' differences give the
    // variance of their mean. 5 standard errors, plus float rounding.
    constexpr double kPixels = kSide * kSide;
    for (int c = 0; c < 3; ++c) {
        double rendered = 0.0, variance = 0.0;
        for (uint32_t y = 0; y < kSide; ++y) {
            for (uint32_t x = 0; x < kSide; ++x) {
                const double a = renders[0].pixel(x, y)[c], b = renders[1].pixel(x, y)[c];
                rendered += 0.5 * (a + b) / kPixels;
                variance += 0.25 * (a - b) * (a - b) / (kPixels * kPixels);
            }
        }
        EXPECT_NEAR(rendered, expected[c], 5.0 * std::sqrt(variance) + 1e-5 * expected[c]) << "channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(HalfWidths, SliverLampTest, ::testing::Values(0.002f, 0.005f, 0.01f, 0.03f));

// A one-sided lamp 2e10 wide seen from below its emitting face: its cross product's
// squares leave float range, and its facing must still be found. Emitters only (max
// depth 0): each pixel is the lamp's radiance, exactly.
TEST_F(RenderTest, AHugeOneSidedLampFacesTheWayItsWindingSays) {
    const glm::vec3 le(1.0f, 2.0f, 3.0f);
    TestGltf scene;
    scene.materials = {emissiveMaterial("lamp", le, false)};
    scene.meshes = {quadZ(0.0f, 0.0f, 1.0e10f, 1.0f, false, 0)};
    scene.cameraPosition = glm::vec3(0.0f);
    const Image image = renderFile(scene.write(tempDir(), "huge_lamp"), {.width = 8, .height = 8, .spp = 4, .maxDepth = 0});
    ASSERT_EQ(image.rgb.size(), 8u * 8u * 3u);
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        EXPECT_FLOAT_EQ(image.rgb[i], le[int(i % 3)]) << "value " << i;
    }
}

}  // namespace
}  // namespace vkdr::test
