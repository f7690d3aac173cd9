// The fixed-point sums of shaders/lib/fixed_point.glsl, run on the host, read back by
// src/core/fixed_point_value.h: a float is held exactly (or, below the lowest bit, to
// within it), a sum is the same in any order of its terms and with carries moved at any
// time, it equals the exact sum even beyond float range, and infinities and NaNs read
// back as such; and the device's reading of sums as floats (fixedPointFloatBits) is the
// nearest float to their exact total.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <boost/multiprecision/cpp_int.hpp>
#include <gtest/gtest.h>

#include "core/fixed_point_value.h"
#include "glsl_host.h"

namespace vkdr::test {
namespace {

using Words = std::vector<int64_t>;

// One step of the device's addFixedPointSteps: the atomic addition, done in place.
void addStep(Words& words, glsl::FixedPointAddition& step) {
    const int64_t before = words[step.word];
    words[step.word] += step.value;
    step = glsl::fixedPointAdditionAfter(step, before);
}

// The device's addFixedPointFromOneLane, one thread at a time.
void add(Words& words, float x) {
    glsl::FixedPointAddition step = glsl::fixedPointAdditionOf(glsl::fixedPointTerm(x));
    while (step.word < gpu::kFixedPointWords) addStep(words, step);
    words[gpu::kFixedPointFlagsWord] |= step.flags;
}

// The exact total of `count` sums' words, in units of the lowest bit.
boost::multiprecision::cpp_int exactTotal(const Words& words, size_t count = 1) {
    boost::multiprecision::cpp_int total = 0;
    for (size_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < gpu::kFixedPointWords; ++k) {
            total += boost::multiprecision::cpp_int(words[i * gpu::kFixedPointWordsPerSum + k]) << (32 * k);
        }
    }
    return total;
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

// Threads that add to one sum at once: their steps interleave in any order, and each
// sees the word as the others left it.
TEST(FixedPoint, IsTheExactSumWhenAdditionsInterleave) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-60, 40);
    std::vector<float> terms(20000);
    for (float& x : terms) x = std::ldexp(uniform(random), exponent(random));
    // Words near the carry threshold, so that carries are taken back while other
    // additions come in between.
    Words start(gpu::kFixedPointWordsPerSum, 0);
    start[1] = glsl::kFixedPointCarryAt - 12345;
    start[2] = -(glsl::kFixedPointCarryAt - 1);
    start[3] = glsl::kFixedPointCarryAt - (int64_t(1) << 33);
    Words inOrder = start;
    for (float x : terms) add(inOrder, x);
    Words words = start;
    std::vector<glsl::FixedPointAddition> inFlight;
    size_t nextTerm = 0;
    size_t carriesTakenBack = 0;
    while (nextTerm < terms.size() || !inFlight.empty()) {
        if (nextTerm < terms.size() && (inFlight.size() < 64 || inFlight.empty())) {
            inFlight.push_back(glsl::fixedPointAdditionOf(glsl::fixedPointTerm(terms[nextTerm++])));
        }
        const size_t i = std::uniform_int_distribution<size_t>(0, inFlight.size() - 1)(random);
        if (inFlight[i].word < gpu::kFixedPointWords) {
            addStep(words, inFlight[i]);
            carriesTakenBack += inFlight[i].takesCarryBack ? 1 : 0;
        }
        if (inFlight[i].word == gpu::kFixedPointWords) {
            words[gpu::kFixedPointFlagsWord] |= inFlight[i].flags;
            inFlight.erase(inFlight.begin() + std::ptrdiff_t(i));
        }
    }
    EXPECT_GT(carriesTakenBack, 0u);
    EXPECT_EQ(words[gpu::kFixedPointFlagsWord], 0);
    EXPECT_EQ(exactTotal(words), exactTotal(inOrder));
}

// A carry out of the top word cannot be held: the sum is flagged out of range, with the
// sign of the carry.
TEST(FixedPoint, FlagsACarryOutOfTheTopWord) {
    const uint32_t top = gpu::kFixedPointWords - 1;
    for (int sign : {1, -1}) {
        Words words(gpu::kFixedPointWordsPerSum, 0);
        words[top] = sign * (glsl::kFixedPointCarryAt - 1);
        glsl::FixedPointAddition step = glsl::fixedPointAdditionToWord(top, sign * int64_t(2), 0);
        addStep(words, step);
        EXPECT_EQ(step.word, gpu::kFixedPointWords);
        EXPECT_EQ(step.flags, sign > 0 ? gpu::kFixedPointPositiveOverflow : gpu::kFixedPointNegativeOverflow);
    }
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

// The float that the device reads a sum (or `count` copies of one, `stride` words
// apart) as.
float deviceFloat(const Words& words, size_t count = 1, size_t stride = gpu::kFixedPointWordsPerSum) {
    glsl::FixedPointTotal total = glsl::fixedPointTotalOfNothing();
    for (size_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < gpu::kFixedPointWords; ++k) glsl::addFixedPointWord(total, k, words[i * stride + k]);
        total.flags |= uint32_t(words[i * stride + gpu::kFixedPointFlagsWord]);
    }
    return std::bit_cast<float>(glsl::fixedPointFloatBits(total));
}

// The nearest float to the exact total of `count` sums, ties to even, by big-integer
// arithmetic: the reference for the device's one rounding (the host's long double reading
// rounds twice, which near a tie can give the other neighbour).
float nearestFloat(const Words& words, size_t count) {
    using boost::multiprecision::cpp_int;
    const cpp_int total = exactTotal(words, count);
    if (total == 0) return 0.0f;
    const bool negative = total < 0;
    const cpp_int magnitude = negative ? cpp_int(-total) : total;
    const int bits = int(boost::multiprecision::msb(magnitude)) + 1;
    const int dropped = std::max(0, bits - 24);
    cpp_int significand = magnitude >> dropped;
    if (dropped > 0) {
        const cpp_int rest = magnitude - (significand << dropped), half = cpp_int(1) << (dropped - 1);
        if (rest > half || (rest == half && (significand & 1) != 0)) ++significand;
    }
    const double value = std::ldexp(double(significand.convert_to<uint64_t>()), dropped + gpu::kFixedPointLowestBit);
    const float rounded = value > double(std::numeric_limits<float>::max()) ? INFINITY : float(value);
    return negative ? -rounded : rounded;
}

// Random words as the device leaves them: any magnitude below the carry threshold in any
// word, either sign (runs of borrows make totals near ties), and the top words mostly
// empty so that most totals are floats. Up to twice kGradientCopies sums: a medium's
// sigma_a and sigma_s are read together with the copies of its sigma_t sums.
TEST(FixedPoint, DeviceFloatsAreTheNearestFloatsToTheExactTotals) {
    std::mt19937_64 random(11);
    std::uniform_int_distribution<int> words(1, int(gpu::kFixedPointWords));
    std::uniform_int_distribution<int> bits(0, 52);
    std::uniform_int_distribution<int> copies(1, 2 * int(gpu::kGradientCopies));
    int infinite = 0, finite = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const size_t count = size_t(copies(random));
        Words sums(count * gpu::kFixedPointWordsPerSum, 0);
        const int used = words(random);
        for (size_t i = 0; i < count; ++i) {
            for (int k = 0; k < used; ++k) {
                const int64_t magnitude = int64_t(random() >> (63 - bits(random)));
                sums[i * gpu::kFixedPointWordsPerSum + k] = (random() & 1) ? magnitude : -magnitude;
            }
        }
        const float expected = nearestFloat(sums, count);
        const float device = deviceFloat(sums, count);
        ASSERT_EQ(std::bit_cast<uint32_t>(device), std::bit_cast<uint32_t>(expected))
            << "trial " << trial << ": " << device << " against " << expected;
        (std::isinf(expected) ? infinite : finite)++;
    }
    // Both kinds of total were met.
    EXPECT_GT(infinite, 100);
    EXPECT_GT(finite, 10000);
}

// Words holding n * 2^shift exactly (n below 2^63, shift a multiple of 32), or -n * 2^shift.
Words wordsOf(uint64_t n, uint32_t word, bool negative = false) {
    Words words(gpu::kFixedPointWordsPerSum, 0);
    const int64_t sign = negative ? -1 : 1;
    words[word] = sign * int64_t(n & 0xffffffffu);
    words[word + 1] = sign * int64_t(n >> 32);
    return words;
}

TEST(FixedPoint, DeviceFloatsRoundTiesToEvenAndOverflowToInfinity) {
    // 24 significant bits, then the rounding bit: ties go to the even significand.
    const double unit = std::ldexp(1.0, gpu::kFixedPointLowestBit + 32);  // word 1's weight
    for (bool negative : {false, true}) {
        const double sign = negative ? -1.0 : 1.0;
        EXPECT_EQ(deviceFloat(wordsOf((0x800001ull << 1) | 1, 1, negative)), float(sign * 0x800002 * 2 * unit));
        EXPECT_EQ(deviceFloat(wordsOf((0x800002ull << 1) | 1, 1, negative)), float(sign * 0x800002 * 2 * unit));
        // Below a tie, a bit far down in word 0 rounds away from zero.
        Words justAbove = wordsOf((0x800002ull << 1) | 1, 1, negative);
        justAbove[0] = negative ? -1 : 1;
        EXPECT_EQ(deviceFloat(justAbove), float(sign * 0x800003 * 2 * unit));
        // Exactly representable: no rounding at all.
        EXPECT_EQ(deviceFloat(wordsOf(0xabcdefull, 1, negative)), float(sign * 0xabcdef * unit));
    }
    // The largest float, and its tie with 2^128, which rounds to infinity.
    const float largest = std::numeric_limits<float>::max();
    const uint32_t topWord = uint32_t((127 - 23 - gpu::kFixedPointLowestBit) / 32);
    const int shift = 127 - 23 - gpu::kFixedPointLowestBit - 32 * int(topWord);
    EXPECT_EQ(deviceFloat(wordsOf(0xffffffull << shift, topWord)), largest);
    EXPECT_EQ(deviceFloat(wordsOf(((0xffffffull << 1) | 1) << (shift - 1), topWord)), INFINITY);
    EXPECT_EQ(deviceFloat(wordsOf(((0xffffffull << 1) | 1) << (shift - 1), topWord, true)), -INFINITY);
    EXPECT_EQ(deviceFloat(Words(gpu::kFixedPointWordsPerSum, 0)), 0.0f);
    // Flags: NaN, and an overflow of either sign or both.
    Words flagged(gpu::kFixedPointWordsPerSum, 0);
    flagged[gpu::kFixedPointFlagsWord] = gpu::kFixedPointNaN;
    EXPECT_TRUE(std::isnan(deviceFloat(flagged)));
    flagged[gpu::kFixedPointFlagsWord] = gpu::kFixedPointPositiveOverflow;
    EXPECT_EQ(deviceFloat(flagged), INFINITY);
    flagged[gpu::kFixedPointFlagsWord] = gpu::kFixedPointNegativeOverflow;
    EXPECT_EQ(deviceFloat(flagged), -INFINITY);
    flagged[gpu::kFixedPointFlagsWord] = gpu::kFixedPointPositiveOverflow | gpu::kFixedPointNegativeOverflow;
    EXPECT_TRUE(std::isnan(deviceFloat(flagged)));
}

}  // namespace
}  // namespace vkdr::test
