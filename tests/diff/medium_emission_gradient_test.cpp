// Gradients of what emissive media gather, against finite differences with common random
// numbers: a medium's emission and sigma_a, homogeneous (absorbing only, and scattering)
// and in a density grid, the emission of a channel that nothing attenuates, and each of
// these with an emission grid, in front of an emitter and lit from the side. The loss is L1
// against a target brighter than every pixel, so it is linear in the image: the finite
// difference estimates the gradient of the expected loss exactly as the adjoint does,
// and the tolerance is 5 of their combined standard errors over seeds. The difference is
// the Richardson extrapolation (4 D(h) - D(2h)) / 3 of central differences D at the
// kind's step h and 2h, whose truncation error is O(h^4): a medium that only absorbs
// renders without noise, and D(h)'s own O(h^2) error (0.1 % for sigma_a) would exceed
// the standard errors. The voxels' gradients with an emissive grid, and an emission
// grid's, are in density_gradient_test.cpp.
#include <cmath>

#include "diff/gradient_over_seeds.h"
#include "diff/rendered_loss_gradient.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "test_gltf.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
constexpr uint32_t kSeeds = 16;

struct GlowCase {
    const char* label;
    glm::vec3 sigmaA;
    glm::vec3 sigmaS;
    bool grid;  // the box holds a 4^3 density grid instead of density 1
    const char* parameter;
    bool flame = false;  // an emission grid (flameGrid) multiplies the emission instead of the density
};

void PrintTo(const GlowCase& c, std::ostream* os) {
    *os << c.label;
}

// Voxel centres span the medium's box, x, y in [-0.6, 0.6] and z in [1, 2.2], densities
// from 0.2 to 1.9.
DensityGrid glowGrid() {
    DensityGrid grid;
    grid.name = "density";
    grid.size = glm::ivec3(4);
    const double edge = 1.2 / 3.0;
    grid.indexToLocal = glm::dmat4(glm::dvec4(edge, 0, 0, 0), glm::dvec4(0, edge, 0, 0), glm::dvec4(0, 0, edge, 0),
                                   glm::dvec4(-0.6, -0.6, 1.0, 1.0));
    for (int i = 0; i < 64; ++i) {
        grid.values.push_back(0.2f + 1.7f * float((i * 29) % 13) / 12.0f);
    }
    return grid;
}

// A strength over the same box, 0 at every seventh voxel, up to 1.6.
DensityGrid flameGrid() {
    DensityGrid grid = glowGrid();
    grid.name = "flame";
    for (int i = 0; i < 64; ++i) {
        grid.values[size_t(i)] = i % 7 == 3 ? 0.0f : 0.1f + 1.5f * float((i * 17) % 11) / 10.0f;
    }
    return grid;
}

TestGltf glowScene(const GlowCase& c) {
    TestGltf g;
    nlohmann::json glow = vkdrMediumMaterial("glow", c.sigmaA, c.sigmaS, 0.3f);
    glow["extensions"]["VKDR_participating_media"]["emission"] = {0.8, 0.5, 1.2};
    if (c.grid) {
        glow["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "glow.vdb"}};
    }
    if (c.flame) {
        glow["extensions"]["VKDR_participating_media"]["emissionGrid"] = {{"uri", "flame.vdb"}};
    }
    g.materials = {emissiveMaterial("back", glm::vec3(0.5f, 0.4f, 0.3f), false),
                   emissiveMaterial("side", glm::vec3(6.0f), false), glow};
    TestMesh side = quadZ(0.0f, 0.0f, 0.4f, 0.0f, true, 1);
    for (glm::vec3& p : side.positions) {
        p = glm::vec3(1.5f, p.y, 1.6f + p.x);  // the plane x = 1.5, facing -x
    }
    g.meshes = {quadZ(0.0f, 0.0f, 2.0f, 3.0f, false, 0), side,
                box(glm::vec3(-0.6f, -0.6f, 1.0f), glm::vec3(0.6f, 0.6f, 2.2f), 2)};
    g.yfov = 0.9f;
    return g;
}

class MediumEmissionGradientTest : public RenderTest, public ::testing::WithParamInterface<GlowCase> {};

TEST_P(MediumEmissionGradientTest, AdjointMatchesFiniteDifferences) {
    const GlowCase& c = GetParam();
    const std::filesystem::path dir = tempDir();
    if (c.grid) {
        writeDensityGridVdb(dir / "glow.vdb", glowGrid());
    }
    if (c.flame) {
        writeDensityGridVdb(dir / "flame.vdb", flameGrid());
    }
    Scene scene = loadScene(glowScene(c).write(dir, "glow")).scene;
    Image bright{kSide, kSide, std::vector<float>(kSide * kSide * 3, 20.0f)};
    RenderedLossGradient lg(testContext(), scene, {{"", bright}}, {c.parameter}, {.spp = 32, .maxDepth = 3},
                            LossKind::L1);
    const std::vector<std::vector<MeanAndError>> adjoint = gradientOverSeeds(lg, scene, kSeeds);
    const std::vector<float> values = getParameter(scene, c.parameter);
    const ParameterDescription& kind = *parseParameterName(c.parameter)->description;
    for (size_t component = 0; component < values.size(); ++component) {
        const double h = kind.finiteDifferenceStep(values[component]);
        auto lossAt = [&](double offset, uint32_t seed) {
            std::vector<float> changed = values;
            changed[component] = float(values[component] + offset);
            Scene edited = scene;
            setParameter(edited, c.parameter, changed);
            return lg.loss(edited, seed);
        };
        std::vector<double> differences;
        for (uint32_t seed = 0; seed < kSeeds; ++seed) {
            const double d1 = (lossAt(h, seed) - lossAt(-h, seed)) / (2.0 * h);
            const double d2 = (lossAt(2.0 * h, seed) - lossAt(-2.0 * h, seed)) / (4.0 * h);
            differences.push_back((4.0 * d1 - d2) / 3.0);
        }
        const MeanAndError fd = meanAndError(differences);
        const MeanAndError& ad = adjoint[0][component];
        EXPECT_NEAR(ad.mean, fd.mean, 5.0 * std::hypot(ad.error, fd.error))
            << c.parameter << "[" << component << "]: adjoint " << ad.mean << " +- " << ad.error
            << ", finite difference " << fd.mean << " +- " << fd.error;
        EXPECT_GT(std::abs(fd.mean), 3.0 * fd.error) << c.parameter << "[" << component << "]";
    }
}

// What a medium emits enters the image linearly and changes no decision of a path, so
// with a loss linear in the image the emission's gradient is the same at every emission,
// bit for bit: in particular at 0, where the stages gather nothing until the gradient is
// wanted, and after a renderer built for a scene without emission is given some.
TEST_F(RenderTest, TheEmissionGradientAtZeroIsItsGradientAnywhere) {
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / "glow.vdb", glowGrid());
    for (bool grid : {false, true}) {
        const GlowCase c{"", glm::vec3(0.6f, 1.2f, 0.3f), glm::vec3(0.5f, 1.5f, 1.0f), grid, "media/glow/emission"};
        Scene glowing = loadScene(glowScene(c).write(dir, "glow")).scene;
        Scene dark = glowing;
        setParameter(dark, c.parameter, std::vector<float>{0.0f});
        Image bright{kSide, kSide, std::vector<float>(kSide * kSide * 3, 20.0f)};
        RenderedLossGradient lg(testContext(), dark, {{"", bright}}, {c.parameter}, {.spp = 8, .maxDepth = 3},
                                LossKind::L1);
        const GradientResult atZero = lg.evaluate(dark, 3);
        const GradientResult atSome = lg.evaluate(glowing, 3);
        EXPECT_EQ(atZero.parameters[0].gradient, atSome.parameters[0].gradient) << (grid ? "grid" : "homogeneous");
        EXPECT_LT(atSome.loss, atZero.loss) << "the emission must brighten the image";
    }
}

// A scene-wide fog that attenuates nothing in blue (and emits no blue, as it must): rays
// that leave the scene through it would gather blue emission without end, so the
// gradients leave blue out, and every gradient stays finite.
TEST_F(RenderTest, AFogClearInOneChannelGivesFiniteEmissionGradients) {
    TestGltf g;
    g.materials = {diffuseMaterial("floor", glm::vec3(0.5f))};
    g.meshes = {quadZ(0.0f, 0.0f, 1.0f, 3.0f, false, 0)};
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.1, 0.2, 0.0}}, {"sigma_s", {0.1, 0.0, 0.0}}, {"emission", {1.0, 0.5, 0.0}}};
    g.yfov = 1.2f;
    Scene scene = loadScene(g.write(tempDir(), "fog")).scene;
    Image black{kSide, kSide, std::vector<float>(kSide * kSide * 3, 0.0f)};
    const std::vector<std::string> names = {"media/fog/sigma_a", "media/fog/sigma_s", "media/fog/emission"};
    RenderedLossGradient lg(testContext(), scene, {{"", black}}, names, {.spp = 4, .maxDepth = 3}, LossKind::L2);
    const GradientResult result = lg.evaluate(scene, 0);
    for (const ParameterGradient& p : result.parameters) {
        for (double d : p.gradient) {
            EXPECT_TRUE(std::isfinite(d)) << p.name;
        }
    }
    EXPECT_EQ(result.parameters[2].gradient[2], 0.0) << "blue's emission gradient is infinite and left out";
    EXPECT_GT(result.parameters[2].gradient[0], 0.0);
}

const glm::vec3 kAbsorbing(0.6f, 1.2f, 0.3f);
const glm::vec3 kScattering(0.5f, 1.5f, 1.0f);
const glm::vec3 kAbsorbingRedGreen(0.6f, 1.2f, 0.0f);

INSTANTIATE_TEST_SUITE_P(
    Media, MediumEmissionGradientTest,
    ::testing::Values(GlowCase{"AbsorbingEmission", kAbsorbing, glm::vec3(0.0f), false, "media/glow/emission"},
                      GlowCase{"AbsorbingSigmaA", kAbsorbing, glm::vec3(0.0f), false, "media/glow/sigma_a"},
                      GlowCase{"ScatteringEmission", kAbsorbing, kScattering, false, "media/glow/emission"},
                      GlowCase{"ScatteringSigmaA", kAbsorbing, kScattering, false, "media/glow/sigma_a"},
                      GlowCase{"GridEmission", kAbsorbing, kScattering, true, "media/glow/emission"},
                      GlowCase{"GridSigmaA", kAbsorbing, kScattering, true, "media/glow/sigma_a"},
                      // So thin that its emission is gathered mostly from points along
                      // each segment (medium_emission.glsl).
                      GlowCase{"FaintGridSigmaA", 0.05f * kAbsorbing, 0.05f * kScattering, true,
                               "media/glow/sigma_a"},
                      // Blue neither absorbs nor scatters: its emission gathers the length
                      // (homogeneous) or the density's integral (grid).
                      GlowCase{"UnattenuatedBlueEmission", kAbsorbingRedGreen, glm::vec3(0.0f), false,
                               "media/glow/emission"},
                      GlowCase{"GridUnattenuatedBlueEmission", kAbsorbingRedGreen, glm::vec3(0.0f), true,
                               "media/glow/emission"},
                      // An emission grid in place of the density in the emission.
                      GlowCase{"FlameEmission", kAbsorbingRedGreen, kScattering, false, "media/glow/emission", true},
                      GlowCase{"FlameSigmaA", kAbsorbing, kScattering, false, "media/glow/sigma_a", true},
                      GlowCase{"GridFlameEmission", kAbsorbing, kScattering, true, "media/glow/emission", true},
                      GlowCase{"GridFlameSigmaA", kAbsorbing, kScattering, true, "media/glow/sigma_a", true}),
    [](const ::testing::TestParamInfo<GlowCase>& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace vkdr::test
