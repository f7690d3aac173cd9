#include "render_test_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "bvh/bvh.h"
#include "scene/load_scene.h"

namespace vkdr::test {

namespace {

// The running test's directory for its files, in one of this process: two test runs on
// one machine keep apart. A parameterised test's names hold '/', which would nest
// directories that TearDown does not remove; one level keeps the cleanup whole.
std::filesystem::path testDirectory() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "." + info->name();
    std::replace(name.begin(), name.end(), '/', '-');
    return std::filesystem::temp_directory_path() / ("vkdr_render_tests_" + std::to_string(getpid())) / name;
}

}  // namespace

VulkanContext& testContext() {
    static VulkanContext context(ContextOptions{});
    return context;
}

void RenderTest::SetUp() {
    messagesBefore_ = testContext().validationMessageCount();
}

// A failed test's files stay for a person to look at.
void RenderTest::TearDown() {
    EXPECT_EQ(testContext().validationMessageCount(), messagesBefore_) << "the Vulkan validation layer reported messages";
    if (!HasFailure()) {
        std::error_code ignored;
        std::filesystem::remove_all(testDirectory(), ignored);
        std::filesystem::remove(testDirectory().parent_path(), ignored);  // only once empty
    }
}

std::filesystem::path RenderTest::tempDir() const {
    const std::filesystem::path dir = testDirectory();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

Image renderFile(const std::filesystem::path& scene, const RenderSettings& settings, RenderStats* stats) {
    LoadedScene loaded = loadScene(scene);
    Bvh bvh = buildBvh(loaded.scene.positions, loaded.scene.triangles);
    Renderer renderer(testContext(), loaded.scene, bvh, settings);
    Image image = renderer.render();
    if (stats != nullptr) {
        *stats = renderer.stats();
    }
    return image;
}

PixelStatistics pixelStatistics(const Image& image) {
    const size_t n = size_t(image.width) * image.height;
    glm::dvec3 sum(0.0), sumSquares(0.0);
    for (size_t i = 0; i < n; ++i) {
        glm::dvec3 v(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]);
        sum += v;
        sumSquares += v * v;
    }
    PixelStatistics s;
    s.mean = sum / double(n);
    glm::dvec3 variance = (sumSquares - double(n) * s.mean * s.mean) / double(n - 1);
    s.pixelStdDev = glm::sqrt(glm::max(variance, glm::dvec3(0.0)));
    s.standardError = s.pixelStdDev / std::sqrt(double(n));
    return s;
}

bool allFinite(const Image& image) {
    for (float v : image.rgb) {
        if (!std::isfinite(v)) {
            return false;
        }
    }
    return true;
}

PixelExpectation absorbedEmitter(glm::dvec3 le, glm::dvec3 sigmaA, const std::vector<double>& distances) {
    PixelExpectation e;
    glm::dvec3 sumSquares(0.0);
    for (double d : distances) {
        glm::dvec3 value = le * glm::exp(-sigmaA * d);
        e.mean += value;
        sumSquares += value * value;
    }
    e.mean /= double(distances.size());
    e.sampleVariance = glm::max(sumSquares / double(distances.size()) - e.mean * e.mean, glm::dvec3(0.0));
    return e;
}

void expectPixelsMatch(const Image& image, uint32_t spp, double floatTolerance,
                       const std::function<PixelExpectation(int x, int y)>& expectation) {
    ASSERT_TRUE(allFinite(image));
    glm::dvec3 sumError(0.0), sumVariance(0.0), sumMean(0.0);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            PixelExpectation e = expectation(x, y);
            for (int c = 0; c < 3; ++c) {
                double value = image.pixel(x, y)[c];
                double variance = e.sampleVariance[c] / spp;
                EXPECT_NEAR(value, e.mean[c], 6.0 * std::sqrt(variance) + floatTolerance * e.mean[c])
                    << "pixel " << x << "," << y << " channel " << c;
                sumError[c] += value - e.mean[c];
                sumVariance[c] += variance;
                sumMean[c] += std::abs(e.mean[c]);
            }
        }
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_LE(std::abs(sumError[c]), 4.0 * std::sqrt(sumVariance[c]) + floatTolerance * sumMean[c])
            << "channel " << c;
    }
}

std::array<MeanAndError, 3> pixelOverSeeds(const std::filesystem::path& scene, RenderSettings settings, int renders) {
    settings.width = settings.height = 1;
    LoadedScene loaded = loadScene(scene);
    Bvh bvh = buildBvh(loaded.scene.positions, loaded.scene.triangles);
    Renderer renderer(testContext(), loaded.scene, bvh, settings);
    std::vector<double> channels[3];
    for (int seed = 0; seed < renders; ++seed) {
        renderer.setSeed(uint32_t(seed));
        Image image = renderer.render();
        for (int c = 0; c < 3; ++c) {
            channels[c].push_back(image.rgb[c]);
        }
    }
    return {meanAndError(channels[0]), meanAndError(channels[1]), meanAndError(channels[2])};
}

void expectPixelNear(const std::array<MeanAndError, 3>& pixel, glm::dvec3 expected) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(pixel[c].mean, expected[c], 6.0 * pixel[c].error + 1e-3 * expected[c]) << "channel " << c;
    }
}

}  // namespace vkdr::test
