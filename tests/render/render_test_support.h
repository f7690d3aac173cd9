#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "core/sample_statistics.h"
#include "image/image.h"
#include "render/render_settings.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace vkdr::test {

// One Vulkan context for the whole test binary (device creation dominates tiny tests).
VulkanContext& testContext();

// Fails the test if the validation layer reported anything while it ran.
class RenderTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    std::filesystem::path tempDir() const;

private:
    uint32_t messagesBefore_ = 0;
};

Image renderFile(const std::filesystem::path& scene, const RenderSettings& settings, RenderStats* stats = nullptr);

// Mean of each channel over the pixels, and its standard error, treating pixels as
// independent estimates of one value (true when every pixel has the same expectation).
struct PixelStatistics {
    glm::dvec3 mean{0.0};
    glm::dvec3 standardError{0.0};
    glm::dvec3 pixelStdDev{0.0};
};
PixelStatistics pixelStatistics(const Image& image);

bool allFinite(const Image& image);

// One pixel, rendered `renders` times with seeds 0, 1, ... and `settings` otherwise: each
// channel's mean over the renders and its standard error, from their spread.
std::array<MeanAndError, 3> pixelOverSeeds(const std::filesystem::path& scene, RenderSettings settings, int renders);

// Every channel of `pixel` within 6 of its standard errors of `expected` (the standard
// error of a few renders is itself uncertain), plus 1e-3 relative for quadrature.
void expectPixelNear(const std::array<MeanAndError, 3>& pixel, glm::dvec3 expected);

// A pixel's expected value and the variance of one sample of it.
struct PixelExpectation {
    glm::dvec3 mean{0.0};
    glm::dvec3 sampleVariance{0.0};
};

// A pixel seeing an emitter of radiance `le` through an absorbing medium, averaged over
// the distances its sub-pixel positions travel in the medium. A ray passes a medium that
// does not scatter weighted by its transmittance, so a sample is Le T(d) at the distance
// d of its sub-pixel position: the variance is that of Le T(d) over the pixel.
PixelExpectation absorbedEmitter(glm::dvec3 le, glm::dvec3 sigmaA, const std::vector<double>& distances);

// Every pixel within 6 standard errors of its expectation (plus a relative float
// tolerance), and the sum over the image within 4 standard errors (plus the same tolerance).
void expectPixelsMatch(const Image& image, uint32_t spp, double floatTolerance,
                       const std::function<PixelExpectation(int x, int y)>& expectation);

}  // namespace vkdr::test
