// The gradient noise figure: mean, standard error and relative noise of one estimate,
// from estimates at several seeds.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "bench/gradient_noise.h"

namespace vkdr::test {
namespace {

TEST(GradientNoise, MeanStandardErrorAndRelativeNoiseOfKnownEstimates) {
    // Mean 3; sample variance (4 + 1 + 0 + 1 + 4) / 4 = 2.5.
    const std::vector<double> estimates{1.0, 2.0, 3.0, 4.0, 5.0};
    std::optional<GradientNoise> noise = gradientNoise(estimates);
    ASSERT_TRUE(noise.has_value());
    EXPECT_DOUBLE_EQ(noise->mean, 3.0);
    EXPECT_DOUBLE_EQ(noise->standardError, std::sqrt(2.5 / 5.0));
    ASSERT_TRUE(noise->relativeNoise.has_value());
    EXPECT_DOUBLE_EQ(*noise->relativeNoise, std::sqrt(2.5) / 3.0);
    // A negative gradient has the same relative noise.
    const std::vector<double> negated{-1.0, -2.0, -3.0, -4.0, -5.0};
    EXPECT_DOUBLE_EQ(*gradientNoise(negated)->relativeNoise, std::sqrt(2.5) / 3.0);
}

TEST(GradientNoise, NoneFromFewerThanTwoEstimates) {
    EXPECT_FALSE(gradientNoise(std::vector<double>{}).has_value());
    EXPECT_FALSE(gradientNoise(std::vector<double>{1.0}).has_value());
}

TEST(GradientNoise, NoRelativeNoiseForAZeroMean) {
    std::optional<GradientNoise> zeros = gradientNoise(std::vector<double>{0.0, 0.0, 0.0});
    ASSERT_TRUE(zeros.has_value());
    EXPECT_EQ(zeros->mean, 0.0);
    EXPECT_EQ(zeros->standardError, 0.0);
    EXPECT_FALSE(zeros->relativeNoise.has_value());
    std::optional<GradientNoise> opposite = gradientNoise(std::vector<double>{-1.0, 1.0});
    ASSERT_TRUE(opposite.has_value());
    EXPECT_DOUBLE_EQ(opposite->standardError, 1.0);
    EXPECT_FALSE(opposite->relativeNoise.has_value());
}

TEST(GradientNoise, NothingNonFinite) {
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(gradientNoise(std::vector<double>{1.0, std::nan("")}).has_value());
    EXPECT_FALSE(gradientNoise(std::vector<double>{1.0, inf}).has_value());
    // Finite estimates whose squared deviations overflow.
    EXPECT_FALSE(gradientNoise(std::vector<double>{1e300, -1e300, 1e300}).has_value());
}

}  // namespace
}  // namespace vkdr::test
