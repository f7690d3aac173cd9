// Furnace tests: a camera inside a closed box whose walls emit Le and reflect albedo
// rho sees L = Le / (1 - rho) in every direction, whatever conservative media
// (sigma_a = 0, any sigma_s and g) fill it. Max depth D truncates the Neumann series
// to Le (1 + rho + ... + rho^D). Tolerances come from the image's own standard error:
// every pixel estimates the same value.
#include <cmath>

#include "furnace_scene.h"
#include "render_test_support.h"

namespace vkdr::test {
namespace {

const glm::vec3 kLe = kFurnaceLe;
constexpr int kSide = 24;

class FurnaceTest : public RenderTest {};

TEST_F(FurnaceTest, DiffuseWallsConverge) {
    const glm::vec3 rho(0.5f, 0.3f, 0.7f);
    auto file = furnace(rho).write(tempDir(), "furnace");
    Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = 64, .maxDepth = 400});
    expectUniformRadiance(image, glm::dvec3(kLe) / (1.0 - glm::dvec3(rho)));
}

TEST_F(FurnaceTest, MaxDepthCountsScatteringVertices) {
    const glm::vec3 rho(0.5f, 0.3f, 0.7f);
    auto file = furnace(rho).write(tempDir(), "furnace");
    for (uint32_t depth : {0u, 1u, 2u, 3u}) {
        SCOPED_TRACE("max depth " + std::to_string(depth));
        glm::dvec3 expected(0.0), power(1.0);
        for (uint32_t k = 0; k <= depth; ++k) {
            expected += glm::dvec3(kLe) * power;
            power *= glm::dvec3(rho);
        }
        Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = 32, .maxDepth = depth});
        expectUniformRadiance(image, expected);
        if (depth == 0) {
            // Only emission is seen: no noise at all.
            EXPECT_EQ(pixelStatistics(image).pixelStdDev, glm::dvec3(0.0));
        }
    }
}

TEST_F(FurnaceTest, ScatteringMediaWithNestedMediumConserveRadiance) {
    const glm::vec3 rho(0.5f, 0.5f, 0.5f);
    TestGltf g = furnace(rho);
    g.extensions["VKDR_participating_media"] = {{"name", "fog"},
                                                {"sigma_a", {0.0, 0.0, 0.0}},
                                                {"sigma_s", {0.5, 1.0, 2.0}},
                                                {"g", 0.7}};
    g.materials.push_back(vkdrMediumMaterial("inner", glm::vec3(0.0f), glm::vec3(3.0f, 1.0f, 0.2f), -0.5f));
    g.meshes.push_back(box(glm::vec3(-0.4f, -0.5f, 0.2f), glm::vec3(0.4f, 0.3f, 0.8f), 1));
    auto file = g.write(tempDir(), "furnace");
    Image image = renderFile(file, {.width = kSide, .height = kSide, .spp = 32, .maxDepth = 2000});
    expectUniformRadiance(image, glm::dvec3(kLe) / (1.0 - glm::dvec3(rho)));
}

TEST_F(FurnaceTest, ErrorFallsAsInverseSquareRootOfSamples) {
    const glm::vec3 rho(0.5f, 0.3f, 0.7f);
    auto file = furnace(rho).write(tempDir(), "furnace");
    glm::dvec3 expected = glm::dvec3(kLe) / (1.0 - glm::dvec3(rho));
    auto rmsError = [&](uint32_t spp) {
        Image image = renderFile(file, {.width = 32, .height = 32, .spp = spp, .maxDepth = 400});
        double sum = 0.0;
        for (size_t i = 0; i < image.rgb.size(); ++i) {
            double e = image.rgb[i] - expected[i % 3];
            sum += e * e;
        }
        return std::sqrt(sum / double(image.rgb.size()));
    };
    // 16x the samples: a quarter of the error. The RMS over 3072 values is itself known
    // to about 1/sqrt(2 * 3072) = 1.3 % (more with heavy tails): allow 15 % on the ratio.
    double ratio = rmsError(16) / rmsError(256);
    EXPECT_NEAR(ratio, 4.0, 0.6);
}

}  // namespace
}  // namespace vkdr::test
