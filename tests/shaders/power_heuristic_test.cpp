// The power heuristic of shaders/lib/sampling.glsl: the textbook formula where it is
// representable, and a weight in [0, 1] for any pdf up to infinity, where squaring the
// pdfs would give inf / inf.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "glsl_host.h"

namespace vkdr::test {
namespace {

TEST(PowerHeuristic, IsTheSquaredPdfShare) {
    for (float a : {1e-6f, 0.3f, 1.0f, 7.0f, 2e4f}) {
        for (float b : {0.0f, 1e-6f, 0.5f, 1.0f, 3e3f}) {
            const double expected = double(a) * a / (double(a) * a + double(b) * b);
            EXPECT_NEAR(glsl::powerHeuristic(a, b), expected, 1e-6) << a << ", " << b;
            EXPECT_NEAR(glsl::powerHeuristic(a, b) + glsl::powerHeuristic(b, a), 1.0, 1e-6) << a << ", " << b;
        }
    }
}

TEST(PowerHeuristic, StaysAWeightForExtremePdfs) {
    const float infinity = std::numeric_limits<float>::infinity();
    const float largest = std::numeric_limits<float>::max();
    const float tiny = std::numeric_limits<float>::denorm_min();
    EXPECT_EQ(glsl::powerHeuristic(1e30f, 1.0f), 1.0f);
    EXPECT_EQ(glsl::powerHeuristic(1.0f, 1e30f), 0.0f);
    EXPECT_EQ(glsl::powerHeuristic(infinity, 2.0f), 1.0f);
    EXPECT_EQ(glsl::powerHeuristic(2.0f, infinity), 0.0f);
    EXPECT_FLOAT_EQ(glsl::powerHeuristic(largest, largest), 0.5f);
    EXPECT_FLOAT_EQ(glsl::powerHeuristic(infinity, infinity), 0.5f);
    EXPECT_FLOAT_EQ(glsl::powerHeuristic(tiny, tiny), 0.5f);
    EXPECT_EQ(glsl::powerHeuristic(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(glsl::powerHeuristic(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(glsl::powerHeuristic(1.0f, 0.0f), 1.0f);
}

}  // namespace
}  // namespace vkdr::test
