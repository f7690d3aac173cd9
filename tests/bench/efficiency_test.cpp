// Efficiency: estimates of a relative noise per second, 1 / (noise^2 x time).
#include <gtest/gtest.h>

#include "bench/efficiency.h"

namespace vkdr::test {
namespace {

TEST(Efficiency, IsEstimatesOfThatNoisePerSecond) {
    EXPECT_DOUBLE_EQ(efficiencyOf(0.1, 2.0).value(), 50.0);
    // Four times the samples: half the noise, four times the time, the same efficiency.
    EXPECT_DOUBLE_EQ(efficiencyOf(0.05, 8.0).value(), 50.0);
}

TEST(Efficiency, NoneWhereItIsNotAFinitePositiveNumber) {
    EXPECT_EQ(efficiencyOf(0.0, 1.0), std::nullopt);  // no noise: nothing to compare
    EXPECT_EQ(efficiencyOf(0.1, 0.0), std::nullopt);
    EXPECT_EQ(efficiencyOf(1e-200, 1e-200), std::nullopt);  // the cost underflows to 0
    EXPECT_EQ(efficiencyOf(1e-160, 1.0), std::nullopt);     // its inverse overflows
}

}  // namespace
}  // namespace vkdr::test
