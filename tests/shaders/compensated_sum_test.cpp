// The compensated sums of shaders/lib/compensated_sum.glsl, which hold a path's radiance
// L and the replay's L_rem, run on the host: adding a path's contributions and
// subtracting them again in the same order leaves at most about 2^-47 L per operation,
// and after a tiny factor the light gathered past it survives the subtraction of the
// light before it to within that bound, where one float loses it entirely.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "glsl_host.h"

namespace vkdr::test {
namespace {

using glsl::CompensatedSum;

CompensatedSum zero() {
    return CompensatedSum{glm::vec3(0.0f), glm::vec3(0.0f)};
}

// Floats log-uniform in [low, high).
std::vector<float> logUniform(std::mt19937& random, int count, double low, double high) {
    std::uniform_real_distribution<double> exponent(std::log(low), std::log(high));
    std::vector<float> values;
    for (int i = 0; i < count; ++i) values.push_back(float(std::exp(exponent(random))));
    return values;
}

// 4 operations per contribution (two TwoSums), each off by at most half an ulp of the
// low part, itself at most half an ulp of the sum: 2^-48 of the sum per operation.
double roundingBound(double sum, size_t contributions) {
    return 4.0 * double(contributions) * std::ldexp(sum, -48);
}

TEST(CompensatedSum, SubtractingAPathsContributionsAgainLeavesOnlyTheBoundsRounding) {
    std::mt19937 random(3);
    std::uniform_int_distribution<int> count(1, 18);
    for (int path = 0; path < 20000; ++path) {
        const std::vector<float> contributions = logUniform(random, count(random), 1e-20, 1e3);
        CompensatedSum sum = zero();
        double exact = 0.0;
        for (float c : contributions) {
            sum = glsl::addCompensated(sum, glm::vec3(c));
            exact += c;
        }
        for (float c : contributions) sum = glsl::addCompensated(sum, glm::vec3(-c));
        ASSERT_LE(std::abs(sum.high.x), roundingBound(exact, 2 * contributions.size())) << "path " << path;
    }
}

// Light of ordinary size, then a vertex that keeps 1e-12 of the throughput and light
// past it: once the replay has subtracted the light before the vertex, what is left is
// the light past it. One float keeps none of it.
TEST(CompensatedSum, LightPastATinyFactorSurvivesTheLightBeforeIt) {
    std::mt19937 random(5);
    std::uniform_int_distribution<int> count(1, 6);
    int floatLost = 0;
    for (int path = 0; path < 20000; ++path) {
        const std::vector<float> before = logUniform(random, count(random), 1e-2, 10.0);
        const std::vector<float> past = logUniform(random, count(random), 1e-13, 1e-12);
        CompensatedSum sum = zero();
        float plain = 0.0f;
        double sumBefore = 0.0, sumPast = 0.0;
        for (float c : before) {
            sum = glsl::addCompensated(sum, glm::vec3(c));
            plain += c;
            sumBefore += c;
        }
        for (float c : past) {
            sum = glsl::addCompensated(sum, glm::vec3(c));
            plain += c;
            sumPast += c;
        }
        for (float c : before) {
            sum = glsl::addCompensated(sum, glm::vec3(-c));
            plain -= c;
        }
        const double bound = roundingBound(sumBefore + sumPast, 2 * before.size() + past.size()) +
                             std::ldexp(sumPast, -22);
        ASSERT_NEAR(sum.high.x, sumPast, bound) << "path " << path;
        floatLost += !(std::abs(plain - sumPast) < 0.5 * sumPast);
    }
    EXPECT_GT(floatLost, 19000);  // what the pair is for
}

TEST(CompensatedSum, AnInfiniteSumStaysInfiniteAndNaNStaysNaN) {
    CompensatedSum sum = glsl::addCompensated(zero(), glm::vec3(3e38f, 1.0f, 0.0f));
    sum = glsl::addCompensated(sum, glm::vec3(3e38f, INFINITY, NAN));
    sum = glsl::addCompensated(sum, glm::vec3(1.0f));
    EXPECT_EQ(sum.high.x, INFINITY);
    EXPECT_EQ(sum.high.y, INFINITY);
    EXPECT_TRUE(std::isnan(sum.high.z));
    EXPECT_EQ(sum.low.x, 0.0f);
    EXPECT_EQ(sum.low.y, 0.0f);
}

}  // namespace
}  // namespace vkdr::test
