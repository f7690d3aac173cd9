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

// glTF's COLOR_0 multiplies the base colour factor (its alpha is not used): walls of
// factor 0.8 whose every vertex has colour c reflect 0.8 c.
TEST_F(FurnaceTest, VertexColoursMultiplyTheBaseColour) {
    TestGltf g = furnace(glm::vec3(0.8f));
    const glm::vec4 colour(0.5f, 0.75f, 1.0f, 0.2f);
    g.meshes[0].colors.assign(g.meshes[0].positions.size(), colour);
    Image image =
        renderFile(g.write(tempDir(), "coloured"), {.width = kSide, .height = kSide, .spp = 64, .maxDepth = 400});
    expectUniformRadiance(image, glm::dvec3(kLe) / (1.0 - 0.8 * glm::dvec3(glm::vec3(colour))));
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

// The mean squared error over the pixels and its standard error. The unit is a pixel
// (its three channels' squared errors summed), as the channels of one pixel share their
// paths and are not independent; pixels are.
struct MeanSquaredError {
    double mean = 0.0;
    double standardError = 0.0;
};

MeanSquaredError meanSquaredError(const Image& image, glm::dvec3 expected) {
    const size_t pixels = image.rgb.size() / 3;
    double sum = 0.0, sumOfSquares = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        double u = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double e = image.rgb[3 * i + c] - expected[c];
            u += e * e;
        }
        sum += u;
        sumOfSquares += u * u;
    }
    const double mean = sum / double(pixels);
    const double variance = (sumOfSquares / double(pixels) - mean * mean) * double(pixels) / double(pixels - 1);
    return {mean, std::sqrt(variance / double(pixels))};
}

TEST_F(FurnaceTest, ErrorFallsAtLeastAsInverseSquareRootOfSamples) {
    const glm::vec3 rho(0.5f, 0.3f, 0.7f);
    auto file = furnace(rho).write(tempDir(), "furnace");
    glm::dvec3 expected = glm::dvec3(kLe) / (1.0 - glm::dvec3(rho));
    auto error = [&](uint32_t spp) {
        return meanSquaredError(renderFile(file, {.width = 32, .height = 32, .spp = spp, .maxDepth = 400}), expected);
    };
    // With independent samples the expected squared error is the per-sample variance
    // over spp: 16x the samples give 1/16 of it and a quarter of the RMS error.
    // Stratified sample points (docs/design.md, "Sample points") do at least as well, so
    // the RMS error must fall at least 4 times. The ratio of RMS errors is known to half
    // the relative standard error of the ratio of mean squares; 5 of those (one
    // comparison) bound it, heavy tails included, as the standard errors come from the
    // pixels' own spread.
    const MeanSquaredError few = error(16), many = error(256);
    const double ratio = std::sqrt(few.mean / many.mean);
    const double relativeError =
        0.5 * std::hypot(few.standardError / few.mean, many.standardError / many.mean);
    EXPECT_GT(ratio, 4.0 - 5.0 * 4.0 * relativeError);
}

}  // namespace
}  // namespace vkdr::test
