// KHR_lights_punctual lights and shading normals against closed forms. A diffuse plane
// facing the camera is lit by one light and nothing else: every sample's next-event
// estimate is the exact irradiance times albedo / pi at the point its ray hits, so a
// pixel's expectation and variance are the mean and variance of that closed form over
// the pixel's area (by quadrature); light reflected further escapes to a black background.
#include <cmath>
#include <functional>
#include <numbers>

#include "diff/gradient_over_seeds.h"
#include "diff/rendered_loss_gradient.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

constexpr float kAlbedo = 0.6f;
constexpr float kPlaneZ = 2.0f;       // the plane faces the camera at the origin, looking along +z
constexpr float kYfov = 0.9f;
constexpr int kSide = 16;
constexpr uint32_t kSpp = 256;
constexpr double kFloatTolerance = 2e-5;

TestGltf litPlane() {
    TestGltf g;
    g.materials = {diffuseMaterial("plane", glm::vec3(kAlbedo))};
    g.meshes = {quadZ(0.0f, 0.0f, 50.0f, kPlaneZ, false, 0)};
    g.cameraPosition = glm::vec3(0.0f);
    g.yfov = kYfov;
    return g;
}

// The point of the plane that image position (x, y) in pixels sees, relative to the
// plane's centre; radially symmetric expectations need no sign conventions.
glm::dvec2 planePoint(double x, double y) {
    double t = std::tan(0.5 * kYfov);
    return glm::dvec2((x / kSide * 2.0 - 1.0) * t, (y / kSide * 2.0 - 1.0) * t) * double(kPlaneZ);
}

// Mean and variance over the pixel of the radiance `radiance(point)` (one channel,
// scaled by `rgb`), by a 48 x 48 midpoint rule.
PixelExpectation overPixel(int x, int y, glm::dvec3 rgb, const std::function<double(glm::dvec2)>& radiance) {
    constexpr int kSub = 48;
    double sum = 0.0, sumSquares = 0.0;
    for (int s = 0; s < kSub * kSub; ++s) {
        double value = radiance(planePoint(x + (s % kSub + 0.5) / kSub, y + (s / kSub + 0.5) / kSub));
        sum += value;
        sumSquares += value * value;
    }
    double mean = sum / (kSub * kSub);
    double variance = std::max(0.0, sumSquares / (kSub * kSub) - mean * mean);
    return {mean * rgb, variance * rgb * rgb};
}

// glTF's recommended spot falloff.
double spotFalloff(double cosAngle, double inner, double outer) {
    double t = std::clamp((cosAngle - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    return t * t;
}

nlohmann::json light(const std::string& name, const std::string& type, glm::vec3 color, float intensity) {
    return {{"name", name}, {"type", type}, {"color", {color.x, color.y, color.z}}, {"intensity", intensity}};
}

const glm::vec3 kColor(1.0f, 0.5f, 0.25f);
constexpr float kIntensity = 3.0f;
constexpr double kLightHeight = 0.7;  // the light's distance in front of the plane

// A pixel of the plane lit by a point light kLightHeight in front of the plane point
// (x, y) = `light`, at the plane points `reached` says its light reaches. The camera
// looks along +z with +y up, so the plane point at image position p is at (x, y) = -p.
PixelExpectation pointLitPixelWhere(int x, int y, glm::dvec2 light, const std::function<bool(glm::dvec2)>& reached) {
    return overPixel(x, y, glm::dvec3(kColor) * double(kIntensity), [&](glm::dvec2 p) {
        if (!reached(-p)) {
            return 0.0;
        }
        double d2 = glm::dot(-p - light, -p - light) + kLightHeight * kLightHeight;
        return kAlbedo / std::numbers::pi * kLightHeight / (d2 * std::sqrt(d2));
    });
}

// A pixel of the plane lit by the point light kLightHeight in front of its centre.
PixelExpectation pointLitPixel(int x, int y) {
    return pointLitPixelWhere(x, y, glm::dvec2(0.0), [](glm::dvec2) { return true; });
}
class PunctualLightTest : public RenderTest {};

TEST_F(PunctualLightTest, PointLightIlluminatesAsInverseSquareTimesCosine) {
    TestGltf g = litPlane();
    g.lights = {light("bulb", "point", kColor, kIntensity)};
    g.lightNodes = {{0, glm::vec3(0.0f, 0.0f, kPlaneZ - kLightHeight)}};
    Image image = renderFile(g.write(tempDir(), "point"), {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 3});
    expectPixelsMatch(image, kSpp, kFloatTolerance, pointLitPixel);
}

// In a scene-wide absorbing medium, 1000 from the origin, the light reaching the camera
// is the closed form times exp(-sigma_a) of the camera's distance to the plane point and
// of the point's distance to the light, the whole of both: the shadow ray starts on the
// plane and stops short of the light by 1e-5 of its coordinates (0.01), and its segment
// counts that stretch (its lead-out); skipping it, or a start 0.01 off the plane, would
// make the plane 1 % dark each. The points are rounded to a few units in the last place of their
// coordinates, sigma_a times that bounds the error.
TEST_F(PunctualLightTest, PointLightInAnAbsorbingMediumFillingSpaceFarFromTheOrigin) {
    constexpr double kSigma = 2.0;
    const glm::vec3 shift(1000.0f, 0.0f, 0.0f);
    TestGltf g = litPlane();
    for (glm::vec3& position : g.meshes[0].positions) {
        position += shift;
    }
    g.cameraPosition += shift;
    g.lights = {light("bulb", "point", kColor, kIntensity)};
    g.lightNodes = {{0, shift + glm::vec3(0.0f, 0.0f, kPlaneZ - kLightHeight)}};
    g.extensions["VKDR_participating_media"] = {{"sigma_a", {kSigma, kSigma, kSigma}}};
    Image image = renderFile(g.write(tempDir(), "point"), {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 3});
    const double tolerance = kFloatTolerance + kSigma * 4.0 * 8.0 * 1.1920929e-7 * 1050.0;
    expectPixelsMatch(image, kSpp, tolerance, [](int x, int y) {
        return overPixel(x, y, glm::dvec3(kColor) * double(kIntensity), [](glm::dvec2 p) {
            const double toLight2 = glm::dot(p, p) + kLightHeight * kLightHeight;
            const double toCamera = std::sqrt(glm::dot(p, p) + double(kPlaneZ) * kPlaneZ);
            return kAlbedo / std::numbers::pi * kLightHeight / (toLight2 * std::sqrt(toLight2)) *
                   std::exp(-kSigma * (std::sqrt(toLight2) + toCamera));
        });
    });
}

// A black wall through the camera, which sees it edge on, reaching from z = 0.5 to 1.9
// and `halfWidth` to each side of the view axis, turned `angle` about that axis from the
// plane x = 0. A point light kLightHeight in front of the plane sits `behind` the wall
// along its normal (0: on it). The wall reflects nothing, so the plane's radiance is
// the closed form above where the wall does not block the light, and 0 where it does.
void expectWallByTheLight(const std::filesystem::path& dir, const std::string& name, float halfWidth, float angle,
                          float behind) {
    TestGltf g = litPlane();
    g.materials.push_back(diffuseMaterial("wall", glm::vec3(0.0f)));
    TestMesh wall;
    wall.material = 1;
    const glm::vec3 side = halfWidth * glm::vec3(-std::sin(angle), std::cos(angle), 0.0f);
    const glm::vec3 near(0.0f, 0.0f, 0.5f), far(0.0f, 0.0f, 1.9f);
    wall.positions = {near - side, near + side, far + side, far - side};
    wall.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
    g.meshes.push_back(wall);
    const glm::dvec2 normal(std::cos(angle), std::sin(angle));
    const glm::dvec2 lightPoint = double(behind) * normal;
    g.lights = {light("bulb", "point", kColor, kIntensity)};
    g.lightNodes = {{0, glm::vec3(glm::vec2(lightPoint), kPlaneZ - kLightHeight)}};
    Image image = renderFile(g.write(dir, name), {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 3});
    // The ray from a plane point p to the light crosses the wall's plane a fraction
    // behind / (behind - p.normal) of the way from the light, at z = lightZ + that
    // fraction times kLightHeight: blocked where that is below the wall's top.
    const double top = 1.9 - (kPlaneZ - kLightHeight);
    expectPixelsMatch(image, kSpp, kFloatTolerance, [&](int x, int y) {
        return pointLitPixelWhere(x, y, lightPoint, [&](glm::dvec2 p) {
            double across = glm::dot(p, normal);
            return behind == 0.0f || across >= 0.0 || behind / (behind - across) * kLightHeight >= top;
        });
    });
}

// Every shadow ray ends on the wall's plane, and the wall must not block it: a light on
// a surface lights what faces it. On a wide wall turned from the axes the rays that
// graze it meet its large triangles where rounding puts them.
TEST_F(PunctualLightTest, APointLightOnASurfaceLightsWhatFacesIt) {
    expectWallByTheLight(tempDir(), "narrow", 5.0f, 0.0f, 0.0f);
    expectWallByTheLight(tempDir(), "wide", 50.0f, 0.3f, 0.0f);
}

// A light 5e-4 behind the wide wall, more than twice the rounding of a side 50 from the
// wall's corners (about 1e-4, shaders/lib/bvh_traverse.glsl) plus the shadow ray's
// shortening (1e-4 of its length, at most 1.6e-4 here): the wall hides it from the
// other side.
TEST_F(PunctualLightTest, APointLightJustBehindASurfaceIsHiddenByIt) {
    expectWallByTheLight(tempDir(), "behind", 50.0f, 0.3f, 5e-4f);
}

TEST_F(PunctualLightTest, SpotLightFallsOffBetweenItsCones) {
    const double inner = 0.35, outer = 0.7;
    TestGltf g = litPlane();
    g.lights = {light("spot", "spot", kColor, kIntensity)};
    g.lights[0]["spot"] = {{"innerConeAngle", inner}, {"outerConeAngle", outer}};
    g.lightNodes = {{0, glm::vec3(0.0f, 0.0f, kPlaneZ - kLightHeight), glm::vec3(0.0f, 0.0f, 1.0f)}};
    Image image = renderFile(g.write(tempDir(), "spot"), {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 3});
    expectPixelsMatch(image, kSpp, kFloatTolerance, [&](int x, int y) {
        return overPixel(x, y, glm::dvec3(kColor) * double(kIntensity), [&](glm::dvec2 p) {
            double d2 = glm::dot(p, p) + kLightHeight * kLightHeight;
            double cosAngle = kLightHeight / std::sqrt(d2);
            return kAlbedo / std::numbers::pi * spotFalloff(cosAngle, inner, outer) * cosAngle / d2;
        });
    });
}

// A directional light at angle alpha to the plane's normal; shading normals tilted by
// beta towards it, or none (flat). The plane's radiance is albedo / pi E cos(alpha - beta).
void expectDirectionalLight(const std::filesystem::path& dir, double alpha, std::optional<double> beta) {
    TestGltf g = litPlane();
    if (beta) {
        // The plane faces -z; tilt its normals about the y axis, towards the light.
        g.meshes[0].normals.assign(g.meshes[0].positions.size(),
                                   glm::vec3(float(-std::sin(*beta)), 0.0f, float(-std::cos(*beta))));
    }
    g.lights = {light("sun", "directional", kColor, kIntensity)};
    // Shining along +z, tilted: wi = -direction = (-sin alpha, 0, -cos alpha).
    g.lightNodes = {{0, glm::vec3(0.0f), glm::vec3(float(std::sin(alpha)), 0.0f, float(std::cos(alpha)))}};
    Image image = renderFile(g.write(dir, "sun"), {.width = kSide, .height = kSide, .spp = 16, .maxDepth = 3});
    const double cosine = std::cos(alpha - beta.value_or(0.0));
    expectPixelsMatch(image, 16, kFloatTolerance, [&](int, int) {
        return PixelExpectation{glm::dvec3(kColor) * (double(kIntensity) * kAlbedo / std::numbers::pi * cosine),
                                glm::dvec3(0.0)};
    });
}

// Sunlight through an absorbing slab between the camera and the plane, 1000 from the
// origin: rays go on from each boundary from the point they cross it (passing over its
// triangle), so a pixel is the sun's closed form times exp(-sigma_a thickness / cos)
// along the shadow ray and along the camera's ray. The points where the rays cross the
// slab's faces are rounded to a few units in the last place of their coordinates:
// sigma_a times that over the cosine, at each of the four crossings, bounds the error
// (a ray going on from 1e-5 of the coordinates, 0.01, off each face would be about 4 %
// dark).
TEST_F(PunctualLightTest, SunlightThroughAnAbsorbingSlabFarFromTheOrigin) {
    constexpr double kAlpha = 0.5;
    constexpr double kSigma = 1.0;
    constexpr double kThickness = 1.0;
    const glm::vec3 shift(1000.0f, 0.0f, 0.0f);
    TestGltf g = litPlane();
    g.materials.push_back(vkdrMediumMaterial("slab", glm::vec3(float(kSigma)), glm::vec3(0.0f), 0.0f));
    g.meshes.push_back(box(glm::vec3(-60.0f, -60.0f, 0.5f), glm::vec3(60.0f, 60.0f, 0.5f + float(kThickness)), 1));
    for (TestMesh& mesh : g.meshes) {
        for (glm::vec3& position : mesh.positions) {
            position += shift;
        }
    }
    g.cameraPosition += shift;
    g.lights = {light("sun", "directional", kColor, kIntensity)};
    g.lightNodes = {{0, shift, glm::vec3(float(std::sin(kAlpha)), 0.0f, float(std::cos(kAlpha)))}};
    Image image = renderFile(g.write(tempDir(), "slab"), {.width = kSide, .height = kSide, .spp = 16, .maxDepth = 3});
    const double shadowTransmittance = std::exp(-kSigma * kThickness / std::cos(kAlpha));
    const double sun = kIntensity * kAlbedo / std::numbers::pi * std::cos(kAlpha) * shadowTransmittance;
    const double largest = 1060.0;
    const double tolerance = kFloatTolerance + kSigma * 4.0 * 8.0 * 1.1920929e-7 * largest / std::cos(kAlpha);
    expectPixelsMatch(image, 16, tolerance, [&](int x, int y) {
        return overPixel(x, y, glm::dvec3(kColor) * sun, [](glm::dvec2 p) {
            const double cosView = kPlaneZ / std::sqrt(glm::dot(p, p) + kPlaneZ * kPlaneZ);
            return std::exp(-kSigma * kThickness / cosView);
        });
    });
}

TEST_F(PunctualLightTest, DirectionalLightGivesCosineOfItsAngle) {
    expectDirectionalLight(tempDir(), 0.0, std::nullopt);
    expectDirectionalLight(tempDir(), 0.8, std::nullopt);
}

TEST_F(PunctualLightTest, ShadingNormalsSetTheCosine) {
    expectDirectionalLight(tempDir(), 0.8, 0.5);
    expectDirectionalLight(tempDir(), 0.3, -0.6);  // tilted away from the light
}

TEST_F(PunctualLightTest, LightsBehindTheSurfaceGiveNothingEvenWhereShadingNormalsFaceThem) {
    // The light grazes the plane from behind it (alpha > pi/2); normals tilted towards
    // it would see it, but the geometric surface hides it.
    TestGltf g = litPlane();
    g.meshes[0].normals.assign(g.meshes[0].positions.size(), glm::normalize(glm::vec3(-1.0f, 0.0f, -0.2f)));
    g.lights = {light("sun", "directional", kColor, kIntensity)};
    g.lightNodes = {{0, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, -0.1f)}};
    Image image = renderFile(g.write(tempDir(), "behind"), {.width = 4, .height = 4, .spp = 16, .maxDepth = 3});
    for (float value : image.rgb) {
        EXPECT_EQ(value, 0.0f);
    }
}

TEST_F(PunctualLightTest, DirectionalLightIsExtinguishedByAMediumFillingSpace) {
    TestGltf g = litPlane();
    g.lights = {light("sun", "directional", kColor, kIntensity)};
    g.lightNodes = {{0, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)}};
    g.extensions["VKDR_participating_media"] = {{"sigma_a", {0.01, 0.01, 0.01}}};
    Image image = renderFile(g.write(tempDir(), "fog"), {.width = 4, .height = 4, .spp = 16, .maxDepth = 3});
    for (float value : image.rgb) {
        EXPECT_EQ(value, 0.0f);
    }
}

// The image is linear in each light's intensity, so the L2 loss's gradient with respect
// to light k's channel c is (2 / 3P) sum over pixels of (E[I] - T) E[I_k per unit], with
// E[I_k per unit] the pixel's expectation from light k alone at intensity 1 (quadrature,
// as above). A point light and a directional light together, defined in the other order
// than the nodes place them, check that each gradient reaches its own light's parameter;
// at intensity 0 the point light must still get its gradient.
void expectIntensityGradients(const std::filesystem::path& dir, float bulbIntensity) {
    constexpr int kPixels = 4;
    constexpr double kSunAngle = 0.5;
    constexpr float kSunIrradiance = 0.8f;
    const glm::vec3 kSunColor(0.3f, 1.0f, 0.6f);
    TestGltf g = litPlane();
    g.lights = {light("sun", "directional", kSunColor, kSunIrradiance), light("bulb", "point", kColor, bulbIntensity)};
    g.lightNodes = {{1, glm::vec3(0.0f, 0.0f, kPlaneZ - kLightHeight)},
                    {0, glm::vec3(0.0f), glm::vec3(float(std::sin(kSunAngle)), 0.0f, float(std::cos(kSunAngle)))}};
    Scene scene = loadScene(g.write(dir, "two_lights")).scene;

    // The pixels of a kPixels-wide image are kSide / kPixels of the test's usual ones.
    constexpr int kScale = kSide / kPixels;
    auto bulbPerUnit = [](int x, int y) {
        double sum = 0.0;
        for (int s = 0; s < kScale * kScale; ++s) {
            sum += overPixel(kScale * x + s % kScale, kScale * y + s / kScale, glm::dvec3(1.0), [](glm::dvec2 p) {
                       double d2 = glm::dot(p, p) + kLightHeight * kLightHeight;
                       return kAlbedo / std::numbers::pi * kLightHeight / (d2 * std::sqrt(d2));
                   }).mean.x;
        }
        return sum / double(kScale * kScale);
    };
    const double sunPerUnit = kAlbedo / std::numbers::pi * std::cos(kSunAngle);
    const glm::dvec3 bulb = glm::dvec3(kColor) * double(bulbIntensity);
    const glm::dvec3 sun = glm::dvec3(kSunColor) * double(kSunIrradiance);
    const glm::dvec3 target(0.05, 0.1, 0.02);
    glm::dvec3 bulbGradient(0.0), sunGradient(0.0);
    for (int y = 0; y < kPixels; ++y) {
        for (int x = 0; x < kPixels; ++x) {
            const double perUnit = bulbPerUnit(x, y);
            glm::dvec3 dLossDI = 2.0 * (bulb * perUnit + sun * sunPerUnit - target) / (3.0 * kPixels * kPixels);
            bulbGradient += dLossDI * perUnit;
            sunGradient += dLossDI * sunPerUnit;
        }
    }

    Image targetImage{kPixels, kPixels, std::vector<float>(3 * kPixels * kPixels)};
    for (size_t i = 0; i < targetImage.rgb.size(); ++i) {
        targetImage.rgb[i] = float(target[int(i % 3)]);
    }
    const std::vector<std::string> names = {"lights/bulb/intensity", "lights/sun/intensity"};
    RenderedLossGradient lossGradient(testContext(), scene, {{"", targetImage}}, names, {.spp = 64, .maxDepth = 3},
                                      LossKind::L2);
    const auto gradients = gradientOverSeeds(lossGradient, scene, 8);
    const glm::dvec3 expected[] = {bulbGradient, sunGradient};
    for (size_t p = 0; p < names.size(); ++p) {
        for (int c = 0; c < 3; ++c) {
            const MeanAndError& adjoint = gradients[p][size_t(c)];
            EXPECT_NE(expected[p][c], 0.0);
            EXPECT_NEAR(adjoint.mean, expected[p][c], 5.0 * adjoint.error + kFloatTolerance * std::abs(expected[p][c]))
                << names[p] << "[" << c << "] at bulb intensity " << bulbIntensity << ": standard error "
                << adjoint.error;
        }
    }
}

TEST_F(PunctualLightTest, IntensityGradientsMatchTheClosedForm) {
    expectIntensityGradients(tempDir(), kIntensity);
}

TEST_F(PunctualLightTest, ALightOfIntensityZeroStillHasItsGradient) {
    expectIntensityGradients(tempDir(), 0.0f);
}

}  // namespace
}  // namespace vkdr::test
