// A grid medium in three slabs side by side, lit from the side: a shadow ray from the
// first slab crosses three grid segments, more than the adjoint keeps, and is traced a
// second time for its voxel gradients. With a constant density c the grid is the
// homogeneous medium of coefficients c sigma, whose slabs are one medium to a shadow ray
// (no second trace), so the sum of the voxels' gradients, d loss / d c, must equal
// (sigma_a . d loss / d sigma_a + sigma_s . d loss / d sigma_s) / c of the homogeneous
// scene. Both are means over seeds; the tolerance is 5 combined standard errors. The L1
// loss against a target brighter than every pixel is linear in the image, so both
// estimate the gradient of the expected loss.
#include <cmath>

#include "diff/gradient_over_seeds.h"
#include "diff/rendered_loss_gradient.h"
#include "render_test_support.h"
#include "scene/load_scene.h"
#include "side_lit_medium.h"
#include "test_gltf.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

constexpr int kSide = 8;
constexpr int kVoxels = 6;
constexpr uint32_t kSeeds = 32;
constexpr float kDensity = 1.5f;
const glm::vec3 kSigmaA(0.1f);
const glm::vec3 kSigmaS(0.5f, 0.75f, 1.0f);

// Voxel centres span the medium's box, the slabs' extent, so the density is kDensity
// everywhere inside them.
DensityGrid constantGrid() {
    DensityGrid grid = gridOverMediumBox(kVoxels);
    grid.values.assign(grid.voxelCount(), kDensity);
    return grid;
}

// The slabs, the side light at x = 1.5 facing them, and a dim emitter behind; with
// `grid`, the medium's density is constantGrid, else its coefficients are kDensity times.
TestGltf slabScene(bool grid) {
    TestGltf g;
    const float scale = grid ? 1.0f : kDensity;
    nlohmann::json smoke = vkdrMediumMaterial("smoke", scale * kSigmaA, scale * kSigmaS, 0.3f);
    if (grid) {
        smoke["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "slabs.vdb"}};
    }
    g.materials = {emissiveMaterial("back", glm::vec3(0.2f), false), emissiveMaterial("side", glm::vec3(20.0f), false),
                   smoke};
    g.meshes = {quadZ(0.0f, 0.0f, 2.0f, 3.0f, false, 0), sideEmitter(1)};
    for (glm::vec2 x : {glm::vec2(-0.6f, -0.25f), glm::vec2(-0.175f, 0.175f), glm::vec2(0.25f, 0.6f)}) {
        g.meshes.push_back(box(glm::vec3(x[0], -0.6f, 1.0f), glm::vec3(x[1], 0.6f, 2.2f), 2));
    }
    g.yfov = 0.9f;
    return g;
}

class GridShadowSegmentsTest : public RenderTest {};

TEST_F(GridShadowSegmentsTest, VoxelGradientsSumToTheHomogeneousMediumsDensityDerivative) {
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / "slabs.vdb", constantGrid());
    const Image bright{kSide, kSide, std::vector<float>(kSide * kSide * 3, 10.0f)};
    const RenderSettings settings{.spp = 64, .maxDepth = 3};

    Scene gridScene = loadScene(slabScene(true).write(dir, "grid")).scene;
    RenderedLossGradient gridGradient(testContext(), gridScene, {{"", bright}}, {"media/smoke/density"}, settings,
                                      LossKind::L1);
    const std::vector<std::vector<std::vector<double>>> voxels =
        gradientSamplesOverSeeds(gridGradient, gridScene, kSeeds);
    std::vector<double> byVoxels(kSeeds, 0.0);  // each seed's sum over the voxels
    for (const std::vector<double>& voxel : voxels[0]) {
        for (uint32_t s = 0; s < kSeeds; ++s) byVoxels[s] += voxel[s];
    }

    Scene homogeneousScene = loadScene(slabScene(false).write(dir, "homogeneous")).scene;
    RenderedLossGradient homogeneousGradient(testContext(), homogeneousScene, {{"", bright}},
                                             {"media/smoke/sigma_a", "media/smoke/sigma_s"}, settings, LossKind::L1);
    const std::vector<std::vector<std::vector<double>>> sigma =
        gradientSamplesOverSeeds(homogeneousGradient, homogeneousScene, kSeeds);
    std::vector<double> bySigma(kSeeds, 0.0);  // each seed's d loss / d c
    for (int c = 0; c < 3; ++c) {
        for (uint32_t s = 0; s < kSeeds; ++s) {
            bySigma[s] += (kSigmaA[c] * sigma[0][size_t(c)][s] + kSigmaS[c] * sigma[1][size_t(c)][s]);
        }
    }

    const MeanAndError fromVoxels = meanAndError(byVoxels);
    const MeanAndError homogeneous = meanAndError(bySigma);
    EXPECT_NEAR(fromVoxels.mean, homogeneous.mean, 5.0 * std::hypot(fromVoxels.error, homogeneous.error))
        << "sum of the voxels' gradients " << fromVoxels.mean << " +- " << fromVoxels.error << ", from sigma "
        << homogeneous.mean << " +- " << homogeneous.error;
    EXPECT_GT(std::abs(homogeneous.mean), 10.0 * homogeneous.error);
}

}  // namespace
}  // namespace vkdr::test
