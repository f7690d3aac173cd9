// Emissive media against closed forms. A segment gathers the emission along it,
// int_0^s T(t) j(t) dt = emission (1 - T(s)) / sigma_t (emission times the density's
// integral where sigma_t is 0), exactly in a homogeneous medium, and in a density grid
// blended from ratio tracking's transmittance and points along the segment (with little
// noise where the grid is faint); with an emission grid, whose strength replaces the
// density in the emission, from points along the segment. And furnaces: walls that emit Le and reflect albedo
// rho hold the radiance L* = Le / (1 - rho) everywhere when every medium inside emits
// exactly what it absorbs there, j = sigma_a L*, whatever it scatters: a homogeneous fog
// around a nested smoke plume, and a grid whose loose majorant makes free flight pause.
#include <algorithm>
#include <cmath>

#include "furnace_scene.h"
#include "render_test_support.h"
#include "single_scattering_quadrature.h"
#include "volume/smoke_plume.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {
namespace {

class EmissiveMediumTest : public RenderTest {};

// Light that crosses the box z in [0.5, 4] (the one pixel looks along +z) gathers no
// scattered light at depth 0: the pixel is the medium's emission along 3.5 units.
FogSetup glowingBox() {
    FogSetup fog;
    fog.enclosure = FogSetup::Box{glm::dvec3(-1.0, -1.0, 0.5), glm::dvec3(1.0, 1.0, 4.0)};
    fog.emission = glm::dvec3(1.0, 2.0, 3.0);
    fog.le = glm::dvec3(0.0);
    return fog;
}

constexpr double kBoxDepth = 3.5;

// emission (1 - exp(-sigma_t D)) / sigma_t per channel, emission D where sigma_t is 0.
glm::dvec3 emittedAlong(glm::dvec3 emission, glm::dvec3 sigmaT, double opticalLengthPerSigma) {
    glm::dvec3 out;
    for (int c = 0; c < 3; ++c) {
        out[c] = sigmaT[c] > 0.0 ? emission[c] * -std::expm1(-sigmaT[c] * opticalLengthPerSigma) / sigmaT[c]
                                 : emission[c] * opticalLengthPerSigma;
    }
    return out;
}

TEST_F(EmissiveMediumTest, HomogeneousEmissionMatchesTheClosedForm) {
    FogSetup fog = glowingBox();
    fog.sigmaA = glm::dvec3(0.2, 0.5, 0.0);
    fog.sigmaS = glm::dvec3(0.3, 0.0, 0.0);
    const auto pixel = pixelOverSeeds(fog.scene().write(tempDir(), "glow"), {.spp = 16, .maxDepth = 0}, 4);
    expectPixelNear(pixel, emittedAlong(fog.emission, fog.sigmaA + fog.sigmaS, kBoxDepth));
}

// The density a + b z has its mean over the box at the box's middle, z = 2.25.
TEST_F(EmissiveMediumTest, EmissionFollowingADensityRampMatchesTheClosedForm) {
    FogSetup fog = glowingBox();
    fog.sigmaA = glm::dvec3(0.2, 0.5, 0.0);
    fog.sigmaS = glm::dvec3(0.0, 0.3, 0.0);
    fog.density = FogSetup::LinearDensity{0.3, 0.5, "density.vdb"};
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
    const auto pixel = pixelOverSeeds(fog.scene().write(dir, "glow"), {.spp = 1024, .maxDepth = 0}, 16);
    const double densityIntegral = kBoxDepth * fog.densityAt(glm::dvec3(0.0, 0.0, 2.25));
    expectPixelNear(pixel, emittedAlong(fog.emission, fog.sigmaA + fog.sigmaS, densityIntegral));
}

// A faintly absorbing glowing ramp, whose majorant optical depth along the pixel's ray is
// at most tau = max(sigma_t) max(d) L, about 0.04 (max(d) the grid's largest voxel, two
// voxels beyond the box). Ratio tracking samples a tentative collision on about one
// segment in 1/tau, so (1 - T) / sigma_t alone is 0 on the others: a relative deviation
// of about 1 / sqrt(tau) per sample. The gather gives that closed form a weight of at
// most 1 - exp(-tau) < tau, so its share deviates by less than sqrt(tau). The rest comes
// from points along the segment with the running transmittance to each, which vary with
// where the points fall (for the ramp d = a + b z, by b L / (4 sqrt(12) d_mid) relative)
// and by at most their whole value where a tentative collision falls (probability below
// tau): less than sqrt(tau) again. The bound allows twice the sum of the three, for the
// uncertainty of a standard error from 16 renders.
TEST_F(EmissiveMediumTest, FaintGlowingGridIsGatheredWithLittleNoise) {
    FogSetup fog = glowingBox();
    fog.sigmaA = glm::dvec3(0.002, 0.004, 0.0);
    fog.sigmaS = glm::dvec3(0.001, 0.0, 0.0);
    fog.density = FogSetup::LinearDensity{0.3, 0.5, "density.vdb"};
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
    constexpr int kSpp = 16;
    constexpr int kRenders = 16;
    const auto pixel = pixelOverSeeds(fog.scene().write(dir, "glow"), {.spp = kSpp, .maxDepth = 0}, kRenders);
    const double middleDensity = fog.densityAt(glm::dvec3(0.0, 0.0, 2.25));
    expectPixelNear(pixel, emittedAlong(fog.emission, fog.sigmaA + fog.sigmaS, kBoxDepth * middleDensity));
    const glm::dvec3 sigmaT = fog.sigmaA + fog.sigmaS;
    const double tau =
        std::max(std::max(sigmaT.x, sigmaT.y), sigmaT.z) * fog.densityAt(glm::dvec3(0.0, 0.0, 4.5)) * kBoxDepth;
    const double pointsSpread = fog.density->b * kBoxDepth / (4.0 * std::sqrt(12.0) * middleDensity);
    const double relativeDeviation = pointsSpread + 2.0 * std::sqrt(tau);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(pixel[c].error, 2.0 * relativeDeviation / std::sqrt(kSpp * kRenders) * pixel[c].mean)
            << "channel " << c;
    }
}

// e int_0^L T(s) (A + B s) ds with T(s) = exp(-k s), per channel.
glm::dvec3 emittedAlongRamp(glm::dvec3 emission, glm::dvec3 k, double length, double a, double b) {
    glm::dvec3 out;
    for (int c = 0; c < 3; ++c) {
        const double kl = k[c] * length;
        out[c] = emission[c] * (k[c] > 0.0 ? a * -std::expm1(-kl) / k[c] +
                                                 b * (-std::expm1(-kl) - kl * std::exp(-kl)) / (k[c] * k[c])
                                           : a * length + b * length * length / 2.0);
    }
    return out;
}

// An emission grid's strength f(z) = 0.2 + 0.6 z takes the place of the density in the
// emission, j = emission f, in a homogeneous medium and in a grid of constant density
// (ratio tracking's running transmittance at the emission's points); blue attenuates
// nowhere. The grid reaches beyond the box, whose faces bound what is gathered.
TEST_F(EmissiveMediumTest, EmissionGridRampMatchesTheClosedForm) {
    for (bool densityGrid : {false, true}) {
        FogSetup fog = glowingBox();
        fog.sigmaA = glm::dvec3(0.2, 0.5, 0.0);
        fog.sigmaS = glm::dvec3(0.3, 0.0, 0.0);
        const double density = densityGrid ? 0.8 : 1.0;
        if (densityGrid) {
            fog.density = FogSetup::LinearDensity{density, 0.0, "density.vdb"};
        }
        FogSetup ramp = fog;
        ramp.density = FogSetup::LinearDensity{0.2, 0.6, "flame.vdb"};
        const std::filesystem::path dir = tempDir();
        if (densityGrid) {
            writeDensityGridVdb(dir / fog.density->uri, linearDensityGrid(fog, 0.25));
        }
        writeDensityGridVdb(dir / ramp.density->uri, linearDensityGrid(ramp, 0.25));
        TestGltf g = fog.scene();
        g.materials.back()["extensions"]["VKDR_participating_media"]["emissionGrid"] = {{"uri", "flame.vdb"},
                                                                                         {"grid", "density"}};
        const auto pixel = pixelOverSeeds(g.write(dir, "glow"), {.spp = 1024, .maxDepth = 0}, 16);
        const double z0 = fog.enclosure->lo.z;
        expectPixelNear(pixel, emittedAlongRamp(fog.emission, density * (fog.sigmaA + fog.sigmaS), kBoxDepth,
                                                ramp.densityAt(glm::dvec3(0.0, 0.0, z0)), ramp.density->b));
        if (HasFailure()) {
            ADD_FAILURE() << (densityGrid ? "in a density grid" : "in a homogeneous medium");
            return;
        }
    }
}

const glm::vec3 kRho(0.5f);
const glm::vec3 kFurnaceRadiance = kFurnaceLe / (1.0f - kRho);

TEST_F(EmissiveMediumTest, FurnaceHoldsItsRadianceWithAFogAndAPlumeThatEmitWhatTheyAbsorb) {
    TestGltf g = furnace(kRho);
    const glm::vec3 fogSigmaA(0.3f, 0.6f, 1.2f);
    const glm::vec3 fogEmission = fogSigmaA * kFurnaceRadiance;
    g.extensions["VKDR_participating_media"] = {{"name", "fog"},
                                                {"sigma_a", {fogSigmaA.x, fogSigmaA.y, fogSigmaA.z}},
                                                {"sigma_s", {0.5, 1.0, 0.2}},
                                                {"g", 0.4},
                                                {"emission", {fogEmission.x, fogEmission.y, fogEmission.z}}};
    const glm::vec3 plumeSigmaA(6.0f, 2.0f, 4.0f);
    const glm::vec3 plumeEmission = plumeSigmaA * kFurnaceRadiance;
    nlohmann::json plume = vkdrMediumMaterial("plume", plumeSigmaA, glm::vec3(10.0f, 8.0f, 3.0f), -0.3f);
    plume["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "plume.vdb"}};
    plume["extensions"]["VKDR_participating_media"]["emission"] = {plumeEmission.x, plumeEmission.y,
                                                                   plumeEmission.z};
    g.materials.push_back(plume);
    g.meshes.push_back(box(glm::vec3(-0.6f), glm::vec3(0.6f), 1));
    const std::filesystem::path dir = tempDir();
    writeDensityGridVdb(dir / "plume.vdb", makeSmokePlume(24, 5));
    Image image = renderFile(g.write(dir, "furnace"), {.width = 24, .height = 24, .spp = 32, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kFurnaceRadiance));
}

// Free flight pauses in this medium (grid_medium_test.cpp), which absorbs far more than
// it scatters: a segment that goes on from a pause must not gather again the emission
// the segment that paused gathered up to the same surface (doing so raises the mean
// by some 20 standard errors).
TEST_F(EmissiveMediumTest, FurnaceWithPausesHoldsItsRadiance) {
    const glm::vec3 sigmaA(3000.0f);
    const std::filesystem::path scene = furnaceWithOneDenseVoxelPerCell(
        kRho, {.sigmaA = sigmaA, .sigmaS = glm::vec3(10.0f), .emission = sigmaA * kFurnaceRadiance}, 3, 0.001f,
        tempDir());
    Image image = renderFile(scene, {.width = 12, .height = 12, .spp = 16, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kFurnaceRadiance));
}

}  // namespace
}  // namespace vkdr::test
