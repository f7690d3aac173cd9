// Density grid media against closed forms: single scattering in a medium whose density
// rises linearly along the view axis against quadrature (delta tracking of the camera
// ray, ratio tracking of the light's), a constant grid against the homogeneous medium
// it equals, absorption by a density ramp against Beer-Lambert (ratio tracking),
// furnaces with heterogeneous conservative media: nested, and one whose majorant is so
// loose that free flight pauses at its step bound and continues in the next segment;
// and the refusals of what tracking cannot render right.
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/bvh.h"
#include "expect_error.h"
#include "furnace_scene.h"
#include "render_test_support.h"
#include "single_scattering_quadrature.h"
#include "scene/load_scene.h"
#include "volume/smoke_plume.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

class GridMediumTest : public RenderTest {};

const RenderSettings kSettings{.spp = 8192, .maxDepth = 1};

FogSetup rampFog(double a, double b) {
    FogSetup fog;
    fog.g = 0.3;
    fog.enclosure = FogSetup::Box{glm::dvec3(-1.0, -1.0, 0.5), glm::dvec3(1.0, 1.0, 4.0)};
    fog.density = FogSetup::LinearDensity{a, b, "density.vdb"};
    return fog;
}

std::filesystem::path writeFog(const FogSetup& fog, const std::filesystem::path& dir) {
    if (fog.density) {
        writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
    }
    return fog.scene().write(dir, "fog");
}

TEST_F(GridMediumTest, SingleScatteringInALinearDensityMatchesQuadrature) {
    FogSetup fog = rampFog(0.2, 0.6);
    expectPixelNear(pixelOverSeeds(writeFog(fog, tempDir()), kSettings, 16), singleScattering(fog).radiance);
}

// An albedo grid whose RGB changes along the view axis scales the scattering (and absorbs
// the rest), in a homogeneous medium and in a density ramp.
TEST_F(GridMediumTest, SingleScatteringWithAnAlbedoRampMatchesQuadrature) {
    for (bool densityGrid : {false, true}) {
        FogSetup fog = rampFog(0.2, 0.6);
        if (!densityGrid) {
            fog.density.reset();
        }
        fog.albedo = FogSetup::LinearAlbedo{glm::dvec3(0.9, 0.5, 0.2), glm::dvec3(-0.1, 0.1, 0.15), "albedo.vdb"};
        const std::filesystem::path dir = tempDir();
        writeDensityGridVdb(dir / fog.albedo->uri, linearAlbedoGrid(fog, 0.25));
        expectPixelNear(pixelOverSeeds(writeFog(fog, dir), kSettings, 16), singleScattering(fog).radiance);
        if (HasFailure()) {
            ADD_FAILURE() << (densityGrid ? "in a density ramp" : "in a homogeneous medium");
            return;
        }
    }
}

TEST_F(GridMediumTest, ConstantGridRendersAsTheHomogeneousMedium) {
    constexpr double kDensity = 2.5;
    FogSetup homogeneous = rampFog(1.0, 0.0);
    homogeneous.density.reset();
    FogSetup grid = rampFog(kDensity, 0.0);
    grid.sigmaA /= kDensity;
    grid.sigmaS /= kDensity;
    const std::filesystem::path dir = tempDir();
    std::filesystem::path homogeneousDir = dir / "homogeneous", gridDir = dir / "grid";
    std::filesystem::create_directories(homogeneousDir);
    std::filesystem::create_directories(gridDir);
    const glm::dvec3 expected = singleScattering(homogeneous).radiance;
    auto fromGrid = pixelOverSeeds(writeFog(grid, gridDir), kSettings, 16);
    auto fromHomogeneous = pixelOverSeeds(writeFog(homogeneous, homogeneousDir), kSettings, 16);
    expectPixelNear(fromGrid, expected);
    expectPixelNear(fromHomogeneous, expected);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(fromGrid[c].mean, fromHomogeneous[c].mean,
                    6.0 * std::hypot(fromGrid[c].error, fromHomogeneous[c].error))
            << "channel " << c;
    }
}

// An emitter seen through a box of absorbing medium whose density is a + b z: each
// pixel's expectation is Le exp(-sigma_a integral of the density), averaged over the
// pixel. Ratio tracking estimates the transmittance, so pixels are noisy; the pixels'
// errors are independent estimates of 0.
TEST_F(GridMediumTest, AbsorbingDensityRampMatchesBeerLambert) {
    FogSetup fog = rampFog(0.3, 0.5);
    fog.sigmaS = glm::dvec3(0.0);
    fog.sigmaA = glm::dvec3(0.2, 0.5, 0.9);
    fog.yfov = 0.3;
    constexpr int kSide = 16;
    TestGltf scene = fog.scene();
    scene.materials[0] = emissiveMaterial("lamp", glm::vec3(fog.le), false);
    scene.meshes[0] = quadZ(0.0f, 0.0f, 3.0f, 6.0f, false, 0);
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
    Image image = renderFile(scene.write(dir, "ramp"), {.width = kSide, .height = kSide, .spp = 64, .maxDepth = 1});
    ASSERT_TRUE(allFinite(image));
    Image errors = image;
    const double tanHalf = std::tan(0.5 * fog.yfov);
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            constexpr int kSub = 8;
            glm::dvec3 expected(0.0);
            for (int s = 0; s < kSub * kSub; ++s) {
                double ndcX = (x + (s % kSub + 0.5) / kSub) / kSide * 2.0 - 1.0;
                double ndcY = (y + (s / kSub + 0.5) / kSub) / kSide * 2.0 - 1.0;
                glm::dvec3 direction = glm::normalize(glm::dvec3(-ndcX * tanHalf, -ndcY * tanHalf, 1.0));
                // The box spans z in [0.5, 4]: the ray's length there, times the density at its middle.
                double length = 3.5 / direction.z;
                double integral = length * fog.densityAt(glm::dvec3(0.0, 0.0, 2.25));
                expected += fog.le * glm::exp(-fog.sigmaA * integral);
            }
            expected /= double(kSub * kSub);
            for (int c = 0; c < 3; ++c) {
                errors.rgb[3 * (y * kSide + x) + c] -= float(expected[c]);
            }
        }
    }
    PixelStatistics s = pixelStatistics(errors);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(s.mean[c], 0.0, 5.0 * s.standardError[c] + 1e-5 * fog.le[c]) << "channel " << c;
    }
}

// A furnace holding a smoke plume (sigma_a = 0) inside a scene-wide scattering fog: the
// media conserve radiance, so every pixel sees Le / (1 - albedo).
TEST_F(GridMediumTest, FurnaceWithNestedPlumeConservesRadiance) {
    const glm::vec3 rho(0.5f);
    TestGltf g = furnace(rho);
    g.extensions["VKDR_participating_media"] = {
        {"name", "fog"}, {"sigma_a", {0.0, 0.0, 0.0}}, {"sigma_s", {0.5, 1.0, 2.0}}, {"g", 0.4}};
    nlohmann::json plume = vkdrMediumMaterial("plume", glm::vec3(0.0f), glm::vec3(20.0f, 8.0f, 3.0f), -0.3f);
    plume["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "plume.vdb"}};
    g.materials.push_back(plume);
    g.meshes.push_back(box(glm::vec3(-0.6f), glm::vec3(0.6f), 1));
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / "plume.vdb", makeSmokePlume(24, 5));
    Image image = renderFile(g.write(dir, "furnace"), {.width = 24, .height = 24, .spp = 32, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kFurnaceLe) / (1.0 - glm::dvec3(rho)));
}

// Every majorant cell holds one voxel of density 1 among voxels of 0.001: free flight
// meets thousands of tentative collisions per crossing, pauses at the step bound and
// continues. The medium still conserves radiance.
TEST_F(GridMediumTest, FurnaceWithLooseMajorantPausesAndConservesRadiance) {
    const glm::vec3 rho(0.5f);
    const std::filesystem::path scene = furnaceWithOneDenseVoxelPerCell(rho, {.sigmaS = glm::vec3(3000.0f)}, 3, 0.001f, tempDir());
    Image image = renderFile(scene, {.width = 12, .height = 12, .spp = 16, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kFurnaceLe) / (1.0 - glm::dvec3(rho)));
}

// Every majorant cell holds one voxel of density 1 among voxels of 0, at a rate so high
// (sigma_s 3e5, 1.5e5 tentative collisions per cell crossed) that free flight pauses
// more often than the segment limit allows: camera rays far from the dense voxels are
// cut short. Depth 0 keeps the few that collide from casting shadow rays through the
// grid. A render counts each cut path once, and a gradient evaluation counts the paths
// its film renders, not their replays again.
TEST_F(GridMediumTest, PathsCutByTheSegmentLimitAreCountedOnce) {
    const Scene scene =
        loadScene(furnaceWithOneDenseVoxelPerCell(glm::vec3(0.5f), {.sigmaS = glm::vec3(3.0e5f)}, 0, 0.0f, tempDir())).scene;
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    const RenderSettings settings{.width = 4, .height = 4, .spp = 4, .maxDepth = 0};
    const uint64_t paths = 4 * 4 * 4;

    Renderer renderer(testContext(), scene, bvh, settings);
    const Image image = renderer.render();
    const uint64_t cut = renderer.stats().truncatedPaths;
    EXPECT_GT(cut, paths / 2);
    EXPECT_LE(cut, paths);

    // The density's gradient: that of the medium's emission would ratio-track the whole
    // segment, which this medium makes too long (and the renderer refuses).
    renderer.enableGradients(image, LossKind::L2, DerivativeTargets::of({ParameterKind::Density}));
    renderer.loss();
    const uint64_t cutForLoss = renderer.stats().truncatedPaths;
    EXPECT_GT(cutForLoss, paths / 2);
    EXPECT_LE(cutForLoss, paths);
    renderer.renderWithGradients();
    EXPECT_EQ(renderer.stats().truncatedPaths, cutForLoss);
}

// The same medium glowing: the gathering of its emission ratio-tracks each whole segment
// and cannot pause and continue (it would need more than kMaxTransmittanceSteps steps),
// so the render is refused, naming the medium, rather than returned with those segments'
// emission wrong.
TEST_F(GridMediumTest, SegmentsTooLongToTrackRefuseTheRenderNamingTheMedium) {
    const MediumCoefficients glowing{.sigmaS = glm::vec3(3.0e5f), .emission = glm::vec3(1.0f)};
    const Scene scene = loadScene(furnaceWithOneDenseVoxelPerCell(glm::vec3(0.5f), glowing, 0, 0.0f, tempDir())).scene;
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Renderer renderer(testContext(), scene, bvh, {.width = 4, .height = 4, .spp = 4, .maxDepth = 0});
    try {
        renderer.render();
        FAIL() << "the render was not refused";
    } catch (const Error& e) {
        const std::string expected = "the density grid medium 'sparse' needed more than " +
                                     std::to_string(gpu::kMaxTransmittanceSteps) + " tracking steps";
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

// sigma_a and sigma_s may each be as large as a float holds, but their sum, which a grid
// medium tracks, then is not: the render is refused naming the medium, not returned NaN
// where a voxel of density 0 multiplies it.
TEST_F(GridMediumTest, AnExtinctionBeyondFloatRangeRefusesTheRenderNamingTheMedium) {
    const float large = 2.0e38f;
    const Scene scene = loadScene(furnaceWithOneDenseVoxelPerCell(glm::vec3(0.5f),
                                                                  {.sigmaA = glm::vec3(1.0f, large, 1.0f),
                                                                   .sigmaS = glm::vec3(1.0f, large, 1.0f)},
                                                                  0, 0.0f, tempDir()))
                            .scene;
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    expectErrorMentioning(
        [&] { Renderer(testContext(), scene, bvh, {.width = 4, .height = 4, .spp = 1, .maxDepth = 1}).render(); },
        {"the density grid medium 'sparse' is too dense to render", "2e+38 + 2e+38, channel G",
         "beyond float range"});
}

// A grid whose voxels lie millions of voxels from the file's index origin (moved there,
// with its transform moved back) renders the same bits as at the origin: the device
// counts index coordinates from the grid's box, where a float keeps the fraction within
// a voxel that trilinear lookups read (from 2^23 on, a float holds whole numbers only).
TEST_F(GridMediumTest, AGridFarFromItsIndexOriginRendersAsAtTheOrigin) {
    const std::filesystem::path dir = tempDir();
    const Scene near = loadScene(writeFog(rampFog(0.3, 0.5), dir)).scene;
    const Bvh bvh = buildBvh(near.positions, near.triangles);
    const RenderSettings settings{.width = 16, .height = 16, .spp = 16, .maxDepth = 2};
    const Image expected = Renderer(testContext(), near, bvh, settings).render();
    for (int32_t shift : {(1 << 23) + 12345, (1 << 24) - 4096}) {
        Scene far = near;
        const glm::ivec3 offset(shift, -shift, shift);
        far.densityGrids[0].grid.firstVoxel += offset;
        far.densityGrids[0].indexToWorld *= glm::translate(glm::dmat4(1.0), -glm::dvec3(offset));
        EXPECT_EQ(Renderer(testContext(), far, bvh, settings).render().rgb, expected.rgb) << "moved by " << shift;
    }
}

// The renderer's index arithmetic is in 32 bits: a grid reaching 2^30 is refused,
// including one whose box ends at int32's largest coordinate (where its last index,
// computed in 32 bits, would wrap round).
TEST_F(GridMediumTest, GridsBeyondTheExactIndexRangeAreRefused) {
    Scene scene = loadScene(furnaceWithOneDenseVoxelPerCell(glm::vec3(0.5f), {.sigmaS = glm::vec3(1.0f)}, 0, 0.0f,
                                                           tempDir()))
                      .scene;
    const Bvh bvh = buildBvh(scene.positions, scene.triangles);
    const int32_t width = scene.densityGrids[0].grid.size.x;
    for (int32_t lastX : {(1 << 30), std::numeric_limits<int32_t>::max()}) {
        scene.densityGrids[0].grid.firstVoxel.x = lastX - width + 1;
        try {
            Renderer(testContext(), scene, bvh, {.width = 4, .height = 4, .spp = 1, .maxDepth = 1}).render();
            ADD_FAILURE() << "a grid ending at x = " << lastX << " was rendered";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("index coordinates beyond 1073741823"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace vkdr::test
