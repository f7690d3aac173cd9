// The adjoint pass against central finite differences with common random numbers: base
// colour, the texels of a base colour texture and emission in a scene-wide fog, g, base
// colour and emission with an enclosed medium, and a base colour that starts at zero.
// Both sides are means over 24 seeds; the tolerance is 5 of their combined standard
// errors (Student's t with 23 degrees of freedom exceeds 5 with probability 5e-5; 24
// comparisons: a false alarm has probability about 1e-3) plus the one difference
// between what the two estimate, the squared loss's covariance. A finite difference of
// the loss of one image differentiates E[sum I^2] = sum E[I]^2 + sum Var(I), the adjoint
// (two independent halves of the samples) only the first term. For a parameter that
// scales every path's contribution by the same power of it (emission, and a base colour
// seen at one bounce) the second term's derivative is exactly r = sum Var(I) / sum
// E[I]^2 (over the channel the component changes) times the first's; for the others (several powers mixed, g) r is its scale. The
// test measures r over seeds and allows r |gradient|. The finite difference's step adds
// nothing to that: emission enters the loss quadratically, and the steps of the others
// keep their truncation error below the noise (finiteDifferenceStep). sigma_a and
// sigma_s are checked against quadrature in analytic_gradient_test.cpp instead: with
// common random numbers their finite differences are too noisy at test-sized sample
// counts (a changed sigma re-routes free flights).
#include <cmath>

#include "bvh/bvh.h"
#include "diff/gradient_check.h"
#include "diff/gradient_over_seeds.h"
#include "gradient_scenes.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 12;
constexpr int kSeeds = 24;
constexpr uint32_t kSpp = 32;

// r = sum Var(I) / sum E[I]^2 over the pixels of the image at kSpp samples, estimated
// from renders at kSeeds seeds: per channel, and (in w) over all three.
glm::dvec4 relativeImageVariance(const Scene& scene) {
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Renderer renderer(testContext(), scene, bvh, {.width = kSide, .height = kSide, .spp = kSpp, .maxDepth = 6});
    std::vector<double> sum(kSide * kSide * 3, 0.0), sumOfSquares(sum.size(), 0.0);
    for (int s = 0; s < kSeeds; ++s) {
        renderer.setSeed(uint32_t(s));
        const Image image = renderer.render();
        for (size_t i = 0; i < sum.size(); ++i) {
            sum[i] += image.rgb[i];
            sumOfSquares[i] += double(image.rgb[i]) * image.rgb[i];
        }
    }
    glm::dvec4 variance(0.0), meanSquared(0.0);
    for (size_t i = 0; i < sum.size(); ++i) {
        const double mean = sum[i] / kSeeds;
        const double v = (sumOfSquares[i] - kSeeds * mean * mean) / (kSeeds - 1);
        variance[i % 3] += v;
        meanSquared[i % 3] += mean * mean - v / kSeeds;  // E[mean^2] = E[I]^2 + Var(I) / kSeeds
    }
    variance.w = variance.x + variance.y + variance.z;
    meanSquared.w = meanSquared.x + meanSquared.y + meanSquared.z;
    return variance / meanSquared;
}

// Gives the walls a two-texel base colour texture, repeated across them with texture
// coordinates that change along every face, so both texels are seen.
void textureTheWalls(Scene& scene) {
    scene.textures.push_back({"stripes", 2, 1, {glm::vec4(0.8f, 0.5f, 0.3f, 1.0f), glm::vec4(0.4f, 0.7f, 0.6f, 1.0f)}});
    scene.materials[0].baseColorTexture = 0;
    scene.uvs.clear();
    for (const glm::vec3& p : scene.positions) {
        scene.uvs.push_back(glm::vec2(p.x + p.y + p.z, p.y - p.z) * 0.75f);
    }
}

struct GradientCase {
    const char* label;
    TestGltf (*scene)();
    const char* parameter;
    const char* assignment;                   // optional --set before differentiating
    void (*edit)(Scene& scene) = nullptr;     // optional change the glTF cannot express
};

void PrintTo(const GradientCase& c, std::ostream* os) {
    *os << c.label;
}

class GradientTest : public RenderTest, public ::testing::WithParamInterface<GradientCase> {};

TEST_P(GradientTest, AdjointMatchesFiniteDifferences) {
    const GradientCase& c = GetParam();
    Scene scene = loadScene(c.scene().write(tempDir(), "scene")).scene;
    if (c.edit) {
        c.edit(scene);
    }
    if (c.assignment[0] != '\0') {
        applyAssignment(scene, c.assignment);
    }
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, {c.parameter},
                            {.spp = kSpp, .maxDepth = 6}, LossKind::L2);
    const glm::dvec4 covariance = relativeImageVariance(scene);
    const std::vector<GradientCheckRow> rows = checkGradients(lg, scene, {c.parameter}, kSeeds);
    double finiteDifferenceSum = 0.0, finiteDifferenceVariance = 0.0;
    for (const GradientCheckRow& row : rows) {
        // A colour's component c changes channel c of the image (a texture's texels are
        // colours one after the other); a scalar changes all three.
        const double r = rows.size() % 3 == 0 ? covariance[row.component % 3] : covariance.w;
        double error = std::hypot(row.adjointError, row.finiteDifferenceError);
        EXPECT_NEAR(row.adjoint, row.finiteDifference, 5.0 * error + r * std::abs(row.finiteDifference))
            << row.name << "[" << row.component << "]: adjoint " << row.adjoint << " +- " << row.adjointError
            << ", finite difference " << row.finiteDifference << " +- " << row.finiteDifferenceError;
        EXPECT_GT(std::abs(row.adjoint), 3.0 * row.adjointError) << row.name << "[" << row.component << "]";
        finiteDifferenceSum += row.finiteDifference;
        finiteDifferenceVariance += row.finiteDifferenceError * row.finiteDifferenceError;
    }
    // A test that cannot fail is no test: the finite differences must tell the gradient
    // from zero. Per component they may not: where Russian roulette decides differently
    // at the two steps a seed's difference jumps, so a small component's error can
    // exceed a third of it. Their sum over the components must.
    EXPECT_GT(std::abs(finiteDifferenceSum), 3.0 * std::sqrt(finiteDifferenceVariance)) << c.parameter;
}

INSTANTIATE_TEST_SUITE_P(
    Parameters, GradientTest,
    ::testing::Values(GradientCase{"BaseColorInFog", foggyRoom, "materials/walls/base_color", ""},
                      GradientCase{"TexelsInFog", foggyRoom, "materials/walls/base_color_texture", "",
                                   textureTheWalls},
                      GradientCase{"EmissionInFog", foggyRoom, "lights/lamp/emission", ""},
                      GradientCase{"EnclosedMediumG", smokeRoom, "media/smoke/g", ""},
                      GradientCase{"BaseColorWithEnclosedMedium", smokeRoom, "materials/walls/base_color", ""},
                      GradientCase{"EmissionWithEnclosedMedium", smokeRoom, "lights/lamp/emission", ""},
                      GradientCase{"ZeroBaseColor", foggyRoom, "materials/walls/base_color",
                                   "materials/walls/base_color=0"}),
    [](const ::testing::TestParamInfo<GradientCase>& info) { return std::string(info.param.label); });

// A path that meets sigma_s = 0 or a black wall goes on in derivative mode only for a
// gradient that was asked for; the gradients of the other parameters are the same
// either way, bit for bit. (The fog scatters in red and blue: a fog that scatters in no
// channel is passed through, which the next test covers.)
TEST_F(RenderTest, UnwantedZeroFactorsLeaveTheOtherGradientsAlone) {
    Scene scene = loadScene(foggyRoom().write(tempDir(), "scene")).scene;
    applyAssignment(scene, "media/fog/sigma_s=0.3,0,0.3");
    applyAssignment(scene, "materials/walls/base_color=0.6,0,0.4");
    // Grey, so that dLoss/dI is not zero where the image is black (green everywhere).
    Image grey{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)};
    auto evaluate = [&](const std::vector<std::string>& names) {
        RenderedLossGradient lg(testContext(), scene, {{"", grey}}, names, {.spp = 8, .maxDepth = 6}, LossKind::L2);
        return lg.evaluate(scene, 5);
    };
    const GradientResult alone = evaluate({"media/fog/sigma_a", "lights/lamp/emission"});
    const GradientResult all =
        evaluate({"media/fog/sigma_a", "lights/lamp/emission", "media/fog/sigma_s", "materials/walls/base_color"});
    for (size_t p = 0; p < 2; ++p) {
        for (size_t c : {0, 2}) {  // green light never reaches the camera
            const double a = alone.parameters[p].gradient[c], b = all.parameters[p].gradient[c];
            EXPECT_NE(a, 0.0) << alone.parameters[p].name << "[" << c << "]";
            EXPECT_EQ(a, b) << alone.parameters[p].name << "[" << c << "]";
        }
    }
    EXPECT_NE(all.parameters[2].gradient[1], 0.0);  // derivative mode found green sigma_s's gradient
    EXPECT_NE(all.parameters[3].gradient[1], 0.0);  // and the green base colour's
}

// Each channel of a path follows its own zero factor in derivative mode: a path whose
// green channel follows the fog's green sigma_s (0) still finds, in its red channel, the
// gradient of the walls' red base colour (0), and the other way round. So each
// parameter's gradient estimates the same whether or not the other is asked for: their
// means over seeds agree within 5 combined standard errors.
TEST_F(RenderTest, ZeroFactorsInDifferentChannelsAreEachFollowed) {
    Scene scene = loadScene(foggyRoom().write(tempDir(), "scene")).scene;
    applyAssignment(scene, "media/fog/sigma_s=0.3,0,0.3");
    applyAssignment(scene, "materials/walls/base_color=0,0.5,0.5");
    Image grey{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)};
    auto overSeeds = [&](const std::vector<std::string>& names) {
        RenderedLossGradient lg(testContext(), scene, {{"", grey}}, names, {.spp = 8, .maxDepth = 6}, LossKind::L2);
        return gradientOverSeeds(lg, scene, 12);
    };
    const auto baseColorAlone = overSeeds({"materials/walls/base_color"});
    const auto scatteringAlone = overSeeds({"media/fog/sigma_s"});
    const auto both = overSeeds({"materials/walls/base_color", "media/fog/sigma_s"});
    auto expectSame = [](const MeanAndError& alone, const MeanAndError& together, const char* what) {
        EXPECT_NEAR(alone.mean, together.mean, 5.0 * std::hypot(alone.error, together.error))
            << what << ": alone " << alone.mean << " +- " << alone.error << ", with the other " << together.mean
            << " +- " << together.error;
        EXPECT_GT(std::abs(alone.mean), 3.0 * alone.error) << what;
    };
    expectSame(baseColorAlone[0][0], both[0][0], "base_color[0]");
    expectSame(scatteringAlone[0][1], both[1][1], "sigma_s[1]");
}

// A factor that is positive but tiny (1e-12) has the gradient of a zero one, which
// derivative mode finds: their means over seeds agree within 5 combined standard errors.
// The paths gather light of ordinary size (a wall's or the fog's next event) before the
// tiny factor, so the gradient term there, L_rem / factor, needs L_rem to about 1e-12 of
// L (shaders/lib/compensated_sum.glsl). Both take the same paths (a sigma_t of 0.15 +
// 1e-12 is 0.15 in float) and differ only in how they compute that term, so their
// standard errors must agree too: with L_rem in one float, off by about 6e-8 L, the
// term is noise thousands of times the gradient, whose mean then passes the first check.
TEST_F(RenderTest, TinyFactorsHaveTheGradientsOfZeroOnes) {
    Image grey{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)};
    auto greenGradient = [&](const char* parameter, const std::string& green) {
        Scene scene = loadScene(foggyRoom().write(tempDir(), "scene")).scene;
        applyAssignment(scene, std::string(parameter) + "=0.3," + green + ",0.3");
        RenderedLossGradient lg(testContext(), scene, {{"", grey}}, {parameter}, {.spp = 8, .maxDepth = 6},
                                LossKind::L2);
        return gradientOverSeeds(lg, scene, 12)[0][1];
    };
    for (const char* parameter : {"media/fog/sigma_s", "materials/walls/base_color"}) {
        const MeanAndError tiny = greenGradient(parameter, "1e-12");
        const MeanAndError zero = greenGradient(parameter, "0");
        EXPECT_NEAR(tiny.mean, zero.mean, 5.0 * std::hypot(tiny.error, zero.error))
            << parameter << "[1]: at 1e-12 " << tiny.mean << " +- " << tiny.error << ", at 0 " << zero.mean << " +- "
            << zero.error;
        EXPECT_LT(tiny.error, 2.0 * zero.error) << parameter;
        EXPECT_GT(std::abs(zero.mean), 3.0 * zero.error) << parameter;
    }
}

// A factor below float's least normal number (1e-40) is sent to the device as 0, which
// some operations there would make it and others not: its image, loss and gradients have
// the bits of 0's (where it gave NaN gradients).
TEST_F(RenderTest, SubnormalFactorsRenderAndDifferentiateAsZeroOnes) {
    Image grey{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)};
    auto evaluate = [&](const char* parameter, const std::string& green) {
        Scene scene = loadScene(foggyRoom().write(tempDir(), "scene")).scene;
        applyAssignment(scene, std::string(parameter) + "=0.3," + green + ",0.3");
        RenderedLossGradient lg(testContext(), scene, {{"", grey}}, {parameter}, {.spp = 8, .maxDepth = 6},
                                LossKind::L2);
        return lg.evaluate(scene, 5);
    };
    for (const char* parameter : {"media/fog/sigma_s", "materials/walls/base_color"}) {
        const GradientResult subnormal = evaluate(parameter, "1e-40");
        const GradientResult zero = evaluate(parameter, "0");
        EXPECT_EQ(subnormal.images.at(0).rgb, zero.images.at(0).rgb) << parameter;
        EXPECT_EQ(subnormal.loss, zero.loss) << parameter;
        EXPECT_EQ(subnormal.parameters.at(0).gradient, zero.parameters.at(0).gradient) << parameter;
    }
}

// A fog that scatters in no channel is passed through, weighted by its transmittance,
// unless the gradient of sigma_s is wanted: only sampled collisions find that gradient
// (derivative mode), so then the fog is sampled as any other. Both estimate the same
// gradients of the other parameters: their means over seeds agree within 5 combined
// standard errors, and the sigma_s gradient is found.
TEST_F(RenderTest, AFogThatDoesNotScatterIsPassedThroughUnlessItsScatteringGradientIsWanted) {
    Scene scene = loadScene(foggyRoom().write(tempDir(), "scene")).scene;
    applyAssignment(scene, "media/fog/sigma_s=0");
    Image grey{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.5f)};
    auto overSeeds = [&](const std::vector<std::string>& names) {
        RenderedLossGradient lg(testContext(), scene, {{"", grey}}, names, {.spp = 8, .maxDepth = 6}, LossKind::L2);
        return gradientOverSeeds(lg, scene, 12);
    };
    const auto passedThrough = overSeeds({"media/fog/sigma_a", "lights/lamp/emission"});
    const auto sampled = overSeeds({"media/fog/sigma_a", "lights/lamp/emission", "media/fog/sigma_s"});
    for (size_t p = 0; p < 2; ++p) {
        for (size_t c = 0; c < 3; ++c) {
            const MeanAndError& a = passedThrough[p][c];
            const MeanAndError& b = sampled[p][c];
            EXPECT_NEAR(a.mean, b.mean, 5.0 * std::hypot(a.error, b.error)) << "parameter " << p << "[" << c << "]";
            EXPECT_GT(std::abs(a.mean), 3.0 * a.error) << "parameter " << p << "[" << c << "]";
        }
    }
    for (size_t c = 0; c < 3; ++c) {
        EXPECT_GT(std::abs(sampled[2][c].mean), 3.0 * sampled[2][c].error) << "sigma_s[" << c << "]";
    }
}

}  // namespace
}  // namespace vkdr::test
