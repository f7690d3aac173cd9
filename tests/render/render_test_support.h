#pragma once
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

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

}  // namespace vkdr::test
