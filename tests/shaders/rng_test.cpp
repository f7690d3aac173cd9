// The counter-based generator of shaders/lib/rng.glsl: uniform, decorrelated across
// neighbouring keys and dimensions, and a pure function of its key.
#include <gtest/gtest.h>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;

TEST(RngTest, UniformOverConsecutivePixels) {
    constexpr int kBins = 256;
    constexpr uint kSamples = 1u << 20;
    std::vector<double> counts(kBins, 0.0);
    for (uint i = 0; i < kSamples; ++i) {
        vec4 u = uniform4(i, 0u, 0u, kDimCamera, 0u);
        for (int c = 0; c < 4; ++c) {
            ASSERT_GE(u[c], 0.0f);
            ASSERT_LT(u[c], 1.0f);
            counts[int(u[c] * kBins)] += 1.0;
        }
    }
    std::vector<double> expected(kBins, 4.0 * kSamples / kBins);
    int dof;
    double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof));
}

TEST(RngTest, PairsOfDimensionsFillTheSquare) {
    // 2D uniformity of (u.x, u.y) and of the same dimension at neighbouring segments.
    constexpr int kSide = 32;
    constexpr uint kSamples = 1u << 19;
    std::vector<double> within(kSide * kSide, 0.0), across(kSide * kSide, 0.0);
    for (uint i = 0; i < kSamples; ++i) {
        vec4 a = uniform4(7u, i, 3u, kDimScatter, 1u);
        vec4 b = uniform4(7u, i, 4u, kDimScatter, 1u);
        within[int(a.x * kSide) * kSide + int(a.y * kSide)] += 1.0;
        across[int(a.x * kSide) * kSide + int(b.x * kSide)] += 1.0;
    }
    std::vector<double> expected(kSide * kSide, double(kSamples) / (kSide * kSide));
    int dof;
    double x2 = chiSquare(within, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof)) << "u.x against u.y";
    x2 = chiSquare(across, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof)) << "u.x against u.x of the next segment";
}

TEST(RngTest, PureFunctionOfKeyAndSeed) {
    EXPECT_EQ(uniform4(1u, 2u, 3u, 1u, 9u), uniform4(1u, 2u, 3u, 1u, 9u));
    EXPECT_NE(uniform4(1u, 2u, 3u, 1u, 9u), uniform4(1u, 2u, 3u, 1u, 10u));
    EXPECT_NE(uniform4(1u, 2u, 3u, 1u, 9u), uniform4(1u, 2u, 3u, 2u, 9u));
    EXPECT_NE(uniform4(1u, 2u, 3u, 1u, 9u), uniform4(1u, 2u, 4u, 1u, 9u));
}

}  // namespace
}  // namespace vkdr::test
