// Per-voxel density gradients against central finite differences with common random
// numbers: a small grid in a box, lit from behind (where the transmittance's derivative
// dominates), from the side (the scattering's) or by its own emission (following the
// density, or an emission grid, whose voxels are tested too), and an albedo grid's voxels
// lit from the side, at voxels inside the medium, on its face, one of zero density
// between denser ones, and voxels of zero density (or albedo) in a region of zeros. The loss is L1
// against a target brighter than every pixel, so it is linear in the image: the finite
// difference estimates the gradient of the expected loss exactly as the adjoint does,
// and both are means over seeds whose standard errors set the tolerance (5 combined
// standard errors per voxel). One voxel denser than all the others holds the majorant
// fixed under the steps.
#include <cmath>

#include "diff/gradient_over_seeds.h"
#include "diff/rendered_loss_gradient.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"
#include "side_lit_medium.h"
#include "test_gltf.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
constexpr int kVoxels = 6;
constexpr uint32_t kSeeds = 32;

size_t voxelIndex(glm::ivec3 v) {
    return size_t(v.x + kVoxels * (v.y + kVoxels * v.z));
}

// Sets the values of the voxels within `reach` of (1, 2, 3) to 0, every channel of them.
void clearAroundTheZeroVoxel(DensityGrid& grid, int reach) {
    const glm::ivec3 centre(1, 2, 3);
    for (int z = centre.z - reach; z <= centre.z + reach; ++z) {
        for (int y = centre.y - reach; y <= centre.y + reach; ++y) {
            for (int x = centre.x - reach; x <= centre.x + reach; ++x) {
                for (int c = 0; c < grid.channels; ++c) {
                    grid.values[voxelIndex({x, y, z}) * size_t(grid.channels) + size_t(c)] = 0.0f;
                }
            }
        }
    }
}

// With `emptyRegion`, the voxels around (1, 2, 3) are 0 as well: nothing scatters
// anywhere near it unless a collision is sampled where the density is 0.
DensityGrid smokeGrid(bool emptyRegion = false) {
    DensityGrid grid = gridOverMediumBox(kVoxels);
    for (int i = 0; i < kVoxels * kVoxels * kVoxels; ++i) {
        grid.values.push_back(0.4f + 1.6f * float((i * 37) % 11) / 10.0f);
    }
    clearAroundTheZeroVoxel(grid, emptyRegion ? 1 : 0);
    // The densest voxel sets the majorant, so that the steps of the voxels under test
    // leave it, and with it the tentative collisions of every path, unchanged.
    grid.values[size_t(4 + kVoxels * (1 + kVoxels * 1))] = 3.0f;
    return grid;
}

// A strength over the same voxels, 0 at the middle one.
DensityGrid flameGrid() {
    DensityGrid grid = smokeGrid();
    grid.name = "flame";
    for (size_t i = 0; i < grid.values.size(); ++i) {
        grid.values[i] = 0.2f + 1.2f * float((i * 23) % 7) / 6.0f;
    }
    grid.values[size_t(2 + kVoxels * (2 + kVoxels * 2))] = 0.0f;
    return grid;
}

// An RGB albedo over the same voxels, from 0.3 to 0.8 in each channel; with
// `zeroRegion`, 0 around (1, 2, 3), where the density is not.
DensityGrid albedoGrid(bool zeroRegion) {
    DensityGrid grid = smokeGrid();
    grid.name = "color";
    grid.channels = 3;
    grid.values.clear();
    for (int i = 0; i < kVoxels * kVoxels * kVoxels; ++i) {
        for (int c = 0; c < 3; ++c) {
            grid.values.push_back(0.3f + 0.5f * float((i * 13 + c * 5) % 9) / 8.0f);
        }
    }
    if (zeroRegion) clearAroundTheZeroVoxel(grid, 1);
    return grid;
}

struct Lighting {
    const char* label;
    float back;  // radiance of the emitter behind the medium
    float side;  // radiance of the emitter beside it
    float sigma;  // scales sigma_a and sigma_s: a thin medium shows its in-scattering
    float glow = 0.0f;  // scales the medium's emission
    const char* parameter = "media/smoke/density";
    bool flame = false;  // an emission grid (flameGrid) multiplies the emission instead of the density
    bool albedo = false;  // an albedo grid (albedoGrid) scales the scattering
    bool emptyRegion = false;  // the grid under test (with `albedo` the albedo grid) is 0 around (1, 2, 3)
};

void PrintTo(const Lighting& lighting, std::ostream* os) {
    *os << lighting.label;
}

TestGltf smokeScene(const Lighting& lighting) {
    TestGltf g;
    nlohmann::json smoke = vkdrMediumMaterial("smoke", lighting.sigma * glm::vec3(0.5f),
                                              lighting.sigma * glm::vec3(2.0f, 3.0f, 4.0f), 0.3f);
    smoke["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "smoke.vdb"}};
    smoke["extensions"]["VKDR_participating_media"]["emission"] = {lighting.glow, 0.6f * lighting.glow,
                                                                   0.3f * lighting.glow};
    if (lighting.flame) {
        smoke["extensions"]["VKDR_participating_media"]["emissionGrid"] = {{"uri", "flame.vdb"}};
    }
    if (lighting.albedo) {
        smoke["extensions"]["VKDR_participating_media"]["albedoGrid"] = {{"uri", "albedo.vdb"}};
    }
    g.materials = {emissiveMaterial("back", lighting.back * glm::vec3(1.0f, 0.8f, 0.6f), false),
                   emissiveMaterial("side", glm::vec3(lighting.side), false), smoke};
    g.meshes = {quadZ(0.0f, 0.0f, 2.0f, 3.0f, false, 0), sideEmitter(1),
                box(glm::vec3(-0.6f, -0.6f, 1.0f), glm::vec3(0.6f, 0.6f, 2.2f), 2)};
    g.yfov = 0.9f;
    return g;
}

class DensityGradientTest : public RenderTest, public ::testing::WithParamInterface<Lighting> {};

TEST_P(DensityGradientTest, AdjointMatchesFiniteDifferences) {
    const std::filesystem::path dir = tempDir();
    const Lighting& lighting = GetParam();
    const char* const kParameter = lighting.parameter;
    writeDensityGridVdb(dir / "smoke.vdb", smokeGrid(lighting.emptyRegion && !lighting.albedo));
    writeDensityGridVdb(dir / "flame.vdb", flameGrid());
    writeDensityGridVdb(dir / "albedo.vdb", albedoGrid(lighting.emptyRegion && lighting.albedo));
    Scene scene = loadScene(smokeScene(lighting).write(dir, "smoke")).scene;
    Image bright{kSide, kSide, std::vector<float>(kSide * kSide * 3, 10.0f)};
    RenderedLossGradient lg(testContext(), scene, {{"", bright}}, {kParameter}, {.spp = 64, .maxDepth = 3},
                            LossKind::L1);
    const std::vector<std::vector<MeanAndError>> adjoint = gradientOverSeeds(lg, scene, kSeeds);

    const std::vector<float> values = getParameter(scene, kParameter);
    // An RGB grid's voxels are tested in one channel each, a different one from voxel to voxel.
    const size_t channels = parseParameterName(kParameter)->description->channels;
    size_t tested = 0;
    for (glm::ivec3 voxel : {glm::ivec3(2, 2, 2), glm::ivec3(1, 2, 3), glm::ivec3(0, 3, 3), glm::ivec3(3, 1, 4)}) {
        // (1, 2, 3) has zero density (in an empty region, so do (2, 2, 2) and (0, 3, 3)), and
        // (2, 2, 2) zero strength in flameGrid.
        const size_t index = voxelIndex(voxel) * channels + tested++ % channels;
        const double value = values[index];
        const double h = value > 0.0 ? 0.2 * value : 0.5;
        auto lossAt = [&](double offset, uint32_t seed) {
            std::vector<float> changed = values;
            changed[index] = float(value + offset);
            Scene edited = scene;
            setParameter(edited, kParameter, changed);
            return lg.loss(edited, seed);
        };
        std::vector<double> differences;
        for (uint32_t seed = 0; seed < kSeeds; ++seed) {
            // Central where the value can step down, else the second-order one-sided difference.
            differences.push_back(value > 0.0 ? (lossAt(h, seed) - lossAt(-h, seed)) / (2.0 * h)
                                              : (-3.0 * lossAt(0.0, seed) + 4.0 * lossAt(h, seed) - lossAt(2.0 * h, seed)) /
                                                    (2.0 * h));
        }
        const MeanAndError fd = meanAndError(differences);
        const MeanAndError& ad = adjoint[0][index];
        EXPECT_NEAR(ad.mean, fd.mean, 5.0 * std::hypot(ad.error, fd.error))
            << "voxel " << voxel.x << " " << voxel.y << " " << voxel.z << " value " << index << ": adjoint " << ad.mean
            << " +- " << ad.error
            << ", finite difference " << fd.mean << " +- " << fd.error;
        EXPECT_GT(std::abs(fd.mean), 3.0 * fd.error) << "voxel " << voxel.x << " " << voxel.y << " " << voxel.z;
    }
}

// A gradient pass that differentiates the density tracks defensively (collisions where
// the density is 0 end their paths, the others weigh more): its image must estimate the
// same as a gradient pass that does not. The L1 loss against a bright target is linear in
// the image; the two passes share their seeds, so their per-seed differences (mean 0)
// set the tolerance, 5 standard errors.
class DefensiveTrackingTest : public RenderTest {};

TEST_F(DefensiveTrackingTest, LeavesTheImageUnbiased) {
    const std::filesystem::path dir = tempDir();
    // Half of the grid empty, so that many camera rays cross where the density is 0 towards
    // the emitter behind.
    DensityGrid grid = smokeGrid();
    for (size_t i = 0; i < grid.values.size(); ++i) {
        if (i % kVoxels < kVoxels / 2) grid.values[i] = 0.0f;
    }
    writeDensityGridVdb(dir / "smoke.vdb", grid);
    Scene scene = loadScene(smokeScene(Lighting{"BackAndSideLit", 1.0f, 20.0f, 0.25f}).write(dir, "smoke")).scene;
    Image bright{kSide, kSide, std::vector<float>(kSide * kSide * 3, 10.0f)};
    const RenderSettings settings{.spp = 64, .maxDepth = 3};
    RenderedLossGradient defensive(testContext(), scene, {{"", bright}}, {"media/smoke/density"}, settings,
                                   LossKind::L1);
    RenderedLossGradient plain(testContext(), scene, {{"", bright}}, {"media/smoke/sigma_a"}, settings, LossKind::L1);
    std::vector<double> differences;
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        differences.push_back(defensive.loss(scene, seed) - plain.loss(scene, seed));
    }
    const MeanAndError difference = meanAndError(differences);
    EXPECT_NEAR(difference.mean, 0.0, 5.0 * difference.error) << difference.mean << " +- " << difference.error;
    EXPECT_GT(difference.error, 0.0) << "the two passes rendered the same image: no defensive tracking";
}

INSTANTIATE_TEST_SUITE_P(Lightings, DensityGradientTest,
                         ::testing::Values(Lighting{"BackLit", 1.0f, 0.0f, 1.0f}, Lighting{"SideLit", 0.0f, 20.0f, 0.25f},
                                           Lighting{"Glowing", 0.0f, 0.0f, 0.5f, 2.0f},
                                           // So thin that its emission is gathered mostly from points
                                           // along each segment (medium_emission.glsl).
                                           Lighting{"FaintlyGlowing", 0.0f, 0.0f, 0.02f, 2.0f},
                                           // With an emission grid: the density's voxels, and the emission grid's
                                           // (the first voxel is the one of zero strength).
                                           Lighting{"GlowingFlameDensity", 0.3f, 0.0f, 1.5f, 2.0f,
                                                    "media/smoke/density", true},
                                           Lighting{"GlowingFlameStrength", 0.0f, 0.0f, 0.5f, 2.0f,
                                                    "media/smoke/emission_grid", true},
                                           // With an albedo grid: its voxels, where the scattering shows.
                                           Lighting{"SideLitAlbedo", 0.0f, 20.0f, 0.25f, 0.0f,
                                                    "media/smoke/albedo_grid", false, true},
                                           // Voxels of density 0 among others of 0: the gradient of
                                           // adding scattering where there is none.
                                           Lighting{"SideLitEmptyRegion", 0.0f, 20.0f, 0.25f, 0.0f,
                                                    "media/smoke/density", false, false, true},
                                           // An albedo of 0 around voxels of albedo 0.
                                           Lighting{"SideLitAlbedoZeroRegion", 0.0f, 20.0f, 0.25f, 0.0f,
                                                    "media/smoke/albedo_grid", false, true, true}),
                         [](const ::testing::TestParamInfo<Lighting>& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace vkdr::test
