// Scene names on the bench command line, and which scenes are too large to try.
#include <gtest/gtest.h>

#include "../image/scratch_directory.h"
#include "bench/bench_scene.h"
#include "expect_error.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

const std::filesystem::path kScenes = VKDR_TEST_SCENES_DIR;

TEST(BenchScene, ShippedScenesAreFoundByName) {
    BenchSceneSource source = resolveBenchScene("cornell_fog", kScenes);
    EXPECT_EQ(source.name, "cornell_fog");
    EXPECT_EQ(source.file, kScenes / "cornell_fog.gltf");
}

TEST(BenchScene, RoomsTakeTheirTriangleCountFromTheName) {
    EXPECT_EQ(resolveBenchScene("room_2500", kScenes).roomTriangles, 2500u);
    EXPECT_EQ(resolveBenchScene("room_10k", kScenes).roomTriangles, 10000u);
    EXPECT_EQ(resolveBenchScene("room_1m", kScenes).roomTriangles, 1000000u);
    EXPECT_TRUE(resolveBenchScene("room_1m", kScenes).file.empty());
}

TEST(BenchScene, FilesAreTakenAsGiven) {
    std::filesystem::path file = kScenes / "cornell_smoke.gltf";
    EXPECT_EQ(resolveBenchScene(file.string(), kScenes).file, file);
    expectErrorMentioning([] { resolveBenchScene("missing/nowhere.glb", kScenes); }, {"missing/nowhere.glb"});
}

TEST(BenchScene, UnknownNamesAreErrorsNamingThem) {
    expectErrorMentioning([] { resolveBenchScene("cornell_fgo", kScenes); }, {"cornell_fgo"});
    expectErrorMentioning([] { resolveBenchScene("room_lots", kScenes); }, {"room_lots"});
    expectErrorMentioning([] { resolveBenchScene("room_0", kScenes); }, {"room_0"});
    expectErrorMentioning([] { resolveBenchScene("room_10x", kScenes); }, {"room_10x"});
    expectErrorMentioning([] { resolveBenchScene("room_5000000m", kScenes); }, {"room_5000000m"});
    expectErrorMentioning([] { resolveBenchScene("room_99999999999999999999999", kScenes); }, {"room_9999"});
}

// What the file system cannot resolve (a loop of links, a name too long) is a scene
// that is not there, named as such: not an exception of the file system's own.
TEST(BenchScene, UnresolvablePathsAreErrorsNamingThem) {
    ScratchDirectory directory;
    std::filesystem::create_symlink(directory / "b", directory / "a");
    std::filesystem::create_symlink(directory / "a", directory / "b");
    const std::string loop = (directory / "a" / "scene.gltf").string();
    expectErrorMentioning([&] { resolveBenchScene(loop, kScenes); }, {loop, "symbolic links"});
    expectErrorMentioning([&] { resolveBenchScene("cornell_fog", directory / "a"); },
                          {"cornell_fog", "symbolic links"});
    expectErrorMentioning([&] { resolveBenchScene("plume_64", directory / "a"); }, {"plume_64", "symbolic links"});
    const std::string longName(300, 'x');
    expectErrorMentioning([&] { resolveBenchScene(longName, kScenes); }, {longName});
}

TEST(BenchScene, PlumesTakeTheirResolutionFromTheName) {
    BenchSceneSource plume = resolveBenchScene("plume_64", kScenes);
    EXPECT_EQ(plume.plumeResolution, 64);
    EXPECT_EQ(plume.file, kScenes / "cornell_plume.gltf");
    EXPECT_EQ(resolveBenchScene("plume_2", kScenes).plumeResolution, 2);
    EXPECT_EQ(resolveBenchScene("plume_1290", kScenes).plumeResolution, 1290);
    EXPECT_EQ(resolveBenchScene("cornell_plume", kScenes).plumeResolution, 0);  // the shipped grid as it is
}

TEST(BenchScene, PlumeNamesOutsideTheGeneratorsRangeAreErrorsNamingThem) {
    for (const char* name : {"plume_0", "plume_1", "plume_1291", "plume_abc", "plume_", "plume_64k", "plume_-64",
                             "plume_64.5", "plume_99999999999999999999"}) {
        expectErrorMentioning([&] { resolveBenchScene(name, kScenes); }, {name});
    }
    expectErrorMentioning([] { resolveBenchScene("plume_64", "/nonexistent"); }, {"plume_64", "cornell_plume.gltf"});
}

TEST(BenchScene, Plume64IsTheShippedPlumeScene) {
    Scene shipped = loadScene(kScenes / "cornell_plume.gltf").scene;
    Scene generated = loadBenchScene(resolveBenchScene("plume_64", kScenes)).scene;
    ASSERT_EQ(generated.densityGrids.size(), 1u);
    const SceneDensityGrid& grid = generated.densityGrids[0];
    EXPECT_EQ(grid.grid.size, shipped.densityGrids[0].grid.size);
    EXPECT_EQ(grid.grid.firstVoxel, shipped.densityGrids[0].grid.firstVoxel);
    EXPECT_EQ(grid.grid.name, shipped.densityGrids[0].grid.name);
    EXPECT_TRUE(grid.grid.values == shipped.densityGrids[0].grid.values);
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            EXPECT_NEAR(grid.indexToWorld[column][row], shipped.densityGrids[0].indexToWorld[column][row], 1e-12);
        }
    }
    EXPECT_EQ(generated.triangles.size(), shipped.triangles.size());
    EXPECT_EQ(generated.media.size(), shipped.media.size());
}

TEST(BenchScene, PlumesOfOtherResolutionsFillTheSameBox) {
    const Scene shipped = loadScene(kScenes / "cornell_plume.gltf").scene;
    const Scene plume = loadBenchScene(resolveBenchScene("plume_24", kScenes)).scene;
    const SceneDensityGrid& grid = plume.densityGrids[0];
    EXPECT_EQ(grid.grid.size, glm::ivec3(24));
    EXPECT_EQ(grid.file, "plume_24");
    // The outer corners of the voxel boxes (index -0.5 and size - 0.5) land on the same points.
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 pick(corner & 1, (corner >> 1) & 1, corner >> 2);
        const glm::dvec3 inShipped = pick * glm::dvec3(shipped.densityGrids[0].grid.size) - 0.5;
        const glm::dvec3 inPlume = pick * glm::dvec3(grid.grid.size) - 0.5;
        const glm::dvec3 expected(shipped.densityGrids[0].indexToWorld * glm::dvec4(inShipped, 1.0));
        const glm::dvec3 actual(grid.indexToWorld * glm::dvec4(inPlume, 1.0));
        EXPECT_LT(glm::length(actual - expected), 1e-9) << corner;
    }
}

TEST(BenchScene, GeneratedRoomHasAboutTheRequestedTriangles) {
    Scene scene = loadBenchScene(resolveBenchScene("room_3k", kScenes)).scene;
    EXPECT_NEAR(double(scene.triangles.size()), 3000.0, 0.05 * 3000.0);
    EXPECT_GE(scene.sceneMedium, 0);
}

// A scene that fits is run; one that does not is skipped naming the memory it lacks.
void expectSkippedForTheMemoryItLacks(const std::string& fits, const std::string& tooLarge) {
    SCOPED_TRACE(tooLarge);
    constexpr uint64_t GiB = uint64_t(1) << 30;
    BenchSceneSource small = resolveBenchScene(fits, kScenes);
    BenchSceneSource huge = resolveBenchScene(tooLarge, kScenes);
    EXPECT_FALSE(whyTooLarge(small, 16 * GiB, 16 * GiB, true));
    std::optional<std::string> host = whyTooLarge(huge, 16 * GiB, 1024 * GiB, false);
    ASSERT_TRUE(host);
    EXPECT_NE(host->find("host memory"), std::string::npos) << *host;
    std::optional<std::string> device = whyTooLarge(huge, 1024 * GiB, 16 * GiB, false);
    ASSERT_TRUE(device);
    EXPECT_NE(device->find("device memory"), std::string::npos) << *device;
    // On a CPU device the device's share counts against the host too.
    const BenchMemoryEstimate estimate = estimateBenchMemory(huge);
    EXPECT_FALSE(whyTooLarge(huge, estimate.hostBytes + estimate.deviceBytes, estimate.deviceHeapBytes, true));
    EXPECT_TRUE(whyTooLarge(huge, estimate.hostBytes + estimate.deviceBytes - 1, estimate.deviceHeapBytes, true));
    EXPECT_TRUE(whyTooLarge(huge, estimate.hostBytes + estimate.deviceBytes, estimate.deviceHeapBytes - 1, true));
}

TEST(BenchScene, RoomsAndPlumesTooLargeForMemoryAreSkippedWithTheReason) {
    expectSkippedForTheMemoryItLacks("room_10k", "room_1000m");
    expectSkippedForTheMemoryItLacks("plume_64", "plume_1290");
    // Shipped scenes and files are not judged before loading.
    EXPECT_FALSE(whyTooLarge(resolveBenchScene("cornell_fog", kScenes), 0, 0, true));
}

// plume_256's peak use fits a 2 GiB heap (lavapipe's), but its density gradient's 1152
// MiB of sums are more than the half of the heap the renderer allows them.
TEST(BenchScene, APlumeWhoseGradientNeedsMoreThanHalfTheHeapIsSkipped) {
    constexpr uint64_t GiB = uint64_t(1) << 30;
    const BenchSceneSource plume = resolveBenchScene("plume_256", kScenes);
    ASSERT_LT(estimateBenchMemory(plume).deviceBytes, 2 * GiB);
    std::optional<std::string> why = whyTooLarge(plume, 64 * GiB, 2 * GiB, false);
    ASSERT_TRUE(why);
    EXPECT_NE(why->find("device memory"), std::string::npos) << *why;
    EXPECT_FALSE(whyTooLarge(plume, 64 * GiB, 3 * GiB, false));
}

TEST(BenchScene, MemoryEstimatesGrowWithTheVoxelCount) {
    const BenchMemoryEstimate small = estimateBenchMemory(resolveBenchScene("plume_64", kScenes));
    const BenchMemoryEstimate large = estimateBenchMemory(resolveBenchScene("plume_128", kScenes));
    EXPECT_EQ(large.deviceBytes, 8 * small.deviceBytes);
    EXPECT_EQ(large.hostBytes, 8 * small.hostBytes);
    // The density gradient alone is 72 bytes a voxel (docs/density-grids.md).
    EXPECT_GT(small.deviceBytes, 72u * 64 * 64 * 64);
    EXPECT_EQ(estimateBenchMemory(resolveBenchScene("cornell_plume", kScenes)).deviceBytes, 0u);
}

}  // namespace
}  // namespace vkdr::test
