// Scene names on the bench command line, and which scenes are too large to try.
#include <gtest/gtest.h>

#include "bench/bench_scene.h"
#include "expect_error.h"

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

TEST(BenchScene, GeneratedRoomHasAboutTheRequestedTriangles) {
    Scene scene = loadBenchScene(resolveBenchScene("room_3k", kScenes));
    EXPECT_NEAR(double(scene.triangles.size()), 3000.0, 0.05 * 3000.0);
    EXPECT_GE(scene.sceneMedium, 0);
}

TEST(BenchScene, RoomsTooLargeForMemoryAreSkippedWithTheReason) {
    constexpr uint64_t GiB = uint64_t(1) << 30;
    BenchSceneSource small = resolveBenchScene("room_10k", kScenes);
    BenchSceneSource huge = resolveBenchScene("room_1000m", kScenes);
    EXPECT_FALSE(whyTooLarge(small, 16 * GiB, 16 * GiB, true));
    std::optional<std::string> host = whyTooLarge(huge, 16 * GiB, 1024 * GiB, false);
    ASSERT_TRUE(host);
    EXPECT_NE(host->find("host memory"), std::string::npos) << *host;
    std::optional<std::string> device = whyTooLarge(huge, 1024 * GiB, 16 * GiB, false);
    ASSERT_TRUE(device);
    EXPECT_NE(device->find("device memory"), std::string::npos) << *device;
    // Shipped scenes and files are not judged before loading.
    EXPECT_FALSE(whyTooLarge(resolveBenchScene("cornell_fog", kScenes), 0, 0, true));
}

}  // namespace
}  // namespace vkdr::test
