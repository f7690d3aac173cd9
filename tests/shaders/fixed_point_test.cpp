// The fixed-point sums of shaders/lib/fixed_point.glsl, run on the host, read back by
// src/core/fixed_point_value.h: a float is held exactly (or, below the lowest bit, to
// within it), a sum is the same in any order of its terms and with carries moved at any
// time, it equals the exact sum even beyond float range, and infinities and NaNs read
// back as such.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/fixed_point_value.h"
#include "glsl_host.h"

namespace vkdr::test {
namespace {

using Words = std::vector<int64_t>;

// The device's addToWord, one thread at a time: add, and move a carry up when the word
// crosses the threshold.
void addToWord(Words& words, uint32_t k, int64_t value) {
    for (;;) {
        const int64_t before = words[k];
        words[k] += value;
        const int64_t carry = glsl::fixedPointCarry(before, words[k]);
        if (carry == 0) return;
        ASSERT_LT(k + 1, gpu::kFixedPointWords) << "a carry out of the top word";
        words[k] -= carry << 32;
        value = carry;
        ++k;
    }
}

void add(Words& words, float x) {
    const glsl::FixedPointTerm term = glsl::fixedPointTerm(x);
    words[gpu::kFixedPointFlagsWord] |= term.flags;
    for (uint32_t k = 0; k < gpu::kFixedPointWords; ++k) {
        const int64_t digit = glsl::fixedPointDigit(term, k);
        if (digit != 0) addToWord(words, k, digit);
    }
}

double sumOf(const std::vector<float>& terms, Words words = Words(gpu::kFixedPointWordsPerSum, 0)) {
    for (float x : terms) add(words, x);
    return fixedPointValue(words);
}

TEST(FixedPoint, HoldsEveryFloatInItsRange) {
    const double lowest = std::ldexp(1.0, gpu::kFixedPointLowestBit);
    for (int exponent = -149; exponent <= 127; ++exponent) {
        for (float mantissa : {1.0f, 1.5f, 1.99999988f, 1.3333334f}) {
            const float x = std::ldexp(mantissa, exponent);
            if (x == 0.0f) continue;
            for (float signed_x : {x, -x}) {
                const double value = sumOf({signed_x});
                if (std::abs(signed_x) >= std::ldexp(1.0, gpu::kFixedPointLowestBit + 23)) {
                    EXPECT_EQ(value, double(signed_x)) << signed_x;
                } else {
                    // Bits below the lowest are truncated toward zero.
                    EXPECT_LT(std::abs(value - signed_x), lowest) << signed_x;
                    EXPECT_LE(std::abs(value), std::abs(double(signed_x))) << signed_x;
                }
            }
        }
    }
    EXPECT_EQ(sumOf({0.0f, -0.0f}), 0.0);
}

TEST(FixedPoint, IsTheExactSumInAnyOrder) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-60, 40);
    std::vector<float> terms(20000);
    // A long double (64-bit mantissa) sum rounds each addition by about 1e-19 of the running
    // sum: 20000 of them stay far below the 1e-12 allowed. No term is small enough to be
    // truncated (the smallest are about 2^-84).
    long double exact = 0.0L;
    for (float& x : terms) {
        x = std::ldexp(uniform(random), exponent(random));
        exact += x;
    }
    const double sum = sumOf(terms);
    EXPECT_NEAR(sum, double(exact), 1e-12 * std::abs(double(exact)));
    for (int shuffle = 0; shuffle < 5; ++shuffle) {
        std::shuffle(terms.begin(), terms.end(), random);
        EXPECT_EQ(sumOf(terms), sum) << "after shuffle " << shuffle;
    }
    // Words that start near the carry threshold: carries move at other moments, the
    // total stays.
    Words nearCarry(gpu::kFixedPointWordsPerSum, 0);
    nearCarry[1] = glsl::kFixedPointCarryAt - 12345;
    nearCarry[2] = -(glsl::kFixedPointCarryAt - 1);
    const double offset = fixedPointValue(nearCarry);
    std::vector<double> sums;
    for (int shuffle = 0; shuffle < 5; ++shuffle) {
        std::shuffle(terms.begin(), terms.end(), random);
        sums.push_back(sumOf(terms, nearCarry));
    }
    for (double s : sums) EXPECT_EQ(s, sums[0]);
    EXPECT_NEAR(sums[0] - offset, sum, 1e-12 * std::abs(offset));
}

TEST(FixedPoint, CopiesSumToTheirTotal) {
    Words copies(3 * gpu::kFixedPointWordsPerSum, 0);
    const float values[3] = {0.25f, -3.5f, 1e-6f};
    for (int copy = 0; copy < 3; ++copy) {
        Words one(gpu::kFixedPointWordsPerSum, 0);
        add(one, values[copy]);
        std::copy(one.begin(), one.end(), copies.begin() + copy * gpu::kFixedPointWordsPerSum);
    }
    EXPECT_DOUBLE_EQ(fixedPointValue(copies, 3), 0.25 - 3.5 + double(1e-6f));
}

// Sums of the largest floats go past float range exactly; only infinities and NaNs are
// not numbers the words hold.
TEST(FixedPoint, HoldsSumsBeyondFloatRangeAndFlagsInfinitiesAndNaN) {
    const float largest = std::numeric_limits<float>::max();
    EXPECT_EQ(sumOf(std::vector<float>(1000, largest)), 1000.0 * double(largest));
    EXPECT_EQ(sumOf(std::vector<float>(1000, -largest)), -1000.0 * double(largest));
    EXPECT_EQ(sumOf({largest, -largest, 2.0f}), 2.0);
    const float infinity = std::numeric_limits<float>::infinity();
    EXPECT_TRUE(std::isnan(sumOf({1.0f, std::numeric_limits<float>::quiet_NaN()})));
    EXPECT_EQ(sumOf({1.0f, infinity}), INFINITY);
    EXPECT_EQ(sumOf({1.0f, -infinity}), -INFINITY);
    EXPECT_TRUE(std::isnan(sumOf({infinity, -infinity})));
}

}  // namespace
}  // namespace vkdr::test
