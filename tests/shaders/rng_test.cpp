// The sample points of shaders/lib/rng.glsl: Sobol's sequence exactly, stratified after
// scrambling, converging faster than independent points, uniform and decorrelated across
// pixels, dimension groups and streams, and a pure function of their key.
#include <gtest/gtest.h>

#include <array>
#include <numbers>

#include "core/sample_statistics.h"
#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;

// Sobol's first four dimensions from Joe and Kuo's table (s, a, m_1..m_s), by their
// integer recurrence m_k = 2 a_1 m_(k-1) ^ ... ^ 2^(s-1) a_(s-1) m_(k-s+1) ^ 2^s m_(k-s)
// ^ m_(k-s), independently of the shader's form.
uint32_t referenceSobol(uint32_t index, int dimension) {
    struct Polynomial {
        int s;
        uint32_t a;
        std::array<uint32_t, 3> m;
    };
    constexpr Polynomial kTable[3] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
    if (dimension == 0) {
        uint32_t result = 0;
        for (int k = 0; k < 32; ++k) {
            result |= ((index >> k) & 1u) << (31 - k);
        }
        return result;
    }
    const Polynomial& p = kTable[dimension - 1];
    std::array<uint64_t, 33> m{};
    for (int k = 1; k <= 32; ++k) {
        if (k <= p.s) {
            m[k] = p.m[k - 1];
            continue;
        }
        uint64_t value = (m[k - p.s] << p.s) ^ m[k - p.s];
        for (int j = 1; j < p.s; ++j) {
            if ((p.a >> (p.s - 1 - j)) & 1u) {
                value ^= m[k - j] << j;
            }
        }
        m[k] = value;
    }
    uint32_t result = 0;
    for (int k = 1; k <= 32; ++k) {
        if ((index >> (k - 1)) & 1u) {
            result ^= uint32_t(m[k] << (32 - k));
        }
    }
    return result;
}

TEST(SampleTest, Sobol4IsSobolsSequence) {
    for (uint32_t index : {0u, 1u, 2u, 3u, 7u, 100u, 4095u, 65537u, 0x7fffffffu, 0xffffffffu}) {
        uvec4 point = sobol4(index);
        for (int d = 0; d < 4; ++d) {
            EXPECT_EQ(point[d], referenceSobol(index, d)) << "index " << index << ", dimension " << d;
        }
    }
    // Joe and Kuo's listing: point 3 (binary 11) is (0.75, 0.25, 0.25, 0.25).
    EXPECT_EQ(sobol4(3u), uvec4(3u << 30, 1u << 30, 1u << 30, 1u << 30));
}

// Whether the points fill every elementary interval of area 1 / points, for each way of
// cutting the square into 2^a by 2^b boxes with a + b = log2(points): a (0, m, 2)-net.
bool isNet(const std::vector<vec2>& points) {
    const int m = std::countr_zero(points.size());
    for (int a = 0; a <= m; ++a) {
        const int cellsX = 1 << a, cellsY = 1 << (m - a);
        std::vector<int> counts(points.size(), 0);
        for (const vec2& p : points) {
            if (++counts[int(p.x * cellsX) * cellsY + int(p.y * cellsY)] > 1) {
                return false;
            }
        }
    }
    return true;
}

// One point per interval of length 1 / points.
bool isStratified(const std::vector<float>& values) {
    std::vector<int> counts(values.size(), 0);
    for (float v : values) {
        if (++counts[int(v * values.size())] > 1) {
            return false;
        }
    }
    return true;
}

TEST(SampleTest, EveryAlignedBlockOfSamplesIsStratified) {
    // Scrambling keeps Sobol's stratification: any 2^m samples from a multiple of 2^m on
    // have their first two dimensions in a (0, m, 2)-net and each dimension in 2^m strata.
    for (uint pixel : {0u, 12345u}) {
        for (uint stream : {0u, 1u}) {
            for (uint m = 1; m <= 10; ++m) {
                for (uint first : {0u, 1u << m, 5u << m}) {
                    std::vector<vec2> xy;
                    std::array<std::vector<float>, 4> each;
                    for (uint i = first; i < first + (1u << m); ++i) {
                        vec4 u = sample4(pixel, i, stream, 4u * 3u + kDimLight, 17u);
                        xy.push_back(vec2(u.x, u.y));
                        for (int d = 0; d < 4; ++d) {
                            each[d].push_back(u[d]);
                        }
                    }
                    SCOPED_TRACE("pixel " + std::to_string(pixel) + ", stream " + std::to_string(stream) +
                                 ", samples " + std::to_string(first) + " + 2^" + std::to_string(m));
                    EXPECT_TRUE(isNet(xy));
                    for (int d = 0; d < 4; ++d) {
                        EXPECT_TRUE(isStratified(each[d])) << "dimension " << d;
                    }
                }
            }
        }
    }
}

// The area of a disk of radius 0.4 in the unit square by `points` samples of the
// dimensions (first, second) of one pixel's sequence.
double diskAreaEstimate(uint pixel, uint points, int first, int second) {
    int inside = 0;
    for (uint i = 0; i < points; ++i) {
        vec4 u = sample4(pixel, i, 0u, kDimScatter, 3u);
        float dx = u[first] - 0.5f, dy = u[second] - 0.5f;
        inside += dx * dx + dy * dy < 0.16f ? 1 : 0;
    }
    return double(inside) / points;
}

TEST(SampleTest, ErrorFallsFasterThanIndependentSamples) {
    // Independent samples' RMS error falls as N^-1/2; scrambled Sobol' points' as N^-3/4
    // for an integrand with an edge. Over 256 pixels (independent scrambles) the RMS error
    // at 16 and at 1024 samples per pixel is known to about 9 % each, while the ratio
    // 1/sqrt(64) = 0.125 that independent samples would give is three times the expected
    // 64^-3/4 = 0.044: every pair of dimensions must beat it.
    constexpr uint kPixels = 256;
    const double area = std::numbers::pi * 0.16;
    for (auto [first, second] : {std::pair{0, 1}, {0, 2}, {1, 3}, {2, 3}}) {
        std::vector<double> squaredErrorFew, squaredErrorMany, estimatesFew;
        for (uint pixel = 0; pixel < kPixels; ++pixel) {
            double few = diskAreaEstimate(pixel, 16, first, second);
            double many = diskAreaEstimate(pixel, 1024, first, second);
            estimatesFew.push_back(few);
            squaredErrorFew.push_back((few - area) * (few - area));
            squaredErrorMany.push_back((many - area) * (many - area));
        }
        SCOPED_TRACE("dimensions " + std::to_string(first) + ", " + std::to_string(second));
        EXPECT_LT(std::sqrt(meanAndError(squaredErrorMany).mean / meanAndError(squaredErrorFew).mean), 0.125);
        // Unbiased: the mean of the estimates within 5 standard errors of the area.
        MeanAndError estimate = meanAndError(estimatesFew);
        EXPECT_NEAR(estimate.mean, area, 5.0 * estimate.error);
    }
}

TEST(SampleTest, UniformOverConsecutivePixels) {
    constexpr int kBins = 256;
    constexpr uint kSamples = 1u << 20;
    std::vector<double> counts(kBins, 0.0);
    for (uint i = 0; i < kSamples; ++i) {
        vec4 u = sample4(i, 0u, 0u, kDimCamera, 0u);
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

TEST(SampleTest, GroupsAndSegmentsAreDecorrelated) {
    // The same dimension of neighbouring groups and segments, sample by sample of one
    // pixel, fills the square uniformly.
    constexpr int kSide = 32;
    constexpr uint kSamples = 1u << 16;
    const uint base = 3u * kDimGroupsPerSegment + kDimFreeFlight;
    for (uint other : {base + 1u, base + kDimGroupsPerSegment}) {
        std::vector<double> counts(kSide * kSide, 0.0);
        for (uint i = 0; i < kSamples; ++i) {
            vec4 a = sample4(7u, i, 0u, base, 1u);
            vec4 b = sample4(7u, i, 0u, other, 1u);
            counts[int(a.x * kSide) * kSide + int(b.x * kSide)] += 1.0;
        }
        std::vector<double> expected(kSide * kSide, double(kSamples) / (kSide * kSide));
        int dof;
        const double x2 = chiSquare(counts, expected, &dof);
        EXPECT_LT(x2, chiSquareCritical(dof)) << "dimension " << other;
    }
}

// Pearson's correlation over pixels of the disk estimates of the first 16 points of
// stream 0 and 16 points of `streamB` from `firstB` on.
double estimateCorrelation(uint streamB, uint firstB) {
    constexpr uint kPixels = 4096, kPoints = 16;
    auto inDisk = [](vec4 u) { return (u.x - 0.5f) * (u.x - 0.5f) + (u.y - 0.5f) * (u.y - 0.5f) < 0.16f ? 1.0 : 0.0; };
    std::vector<double> a, b, ab;
    for (uint pixel = 0; pixel < kPixels; ++pixel) {
        double insideA = 0.0, insideB = 0.0;
        for (uint i = 0; i < kPoints; ++i) {
            insideA += inDisk(sample4(pixel, i, 0u, kDimLight, 5u));
            insideB += inDisk(sample4(pixel, firstB + i, streamB, kDimLight, 5u));
        }
        a.push_back(insideA);
        b.push_back(insideB);
        ab.push_back(insideA * insideB);
    }
    const double meanA = meanAndError(a).mean, meanB = meanAndError(b).mean;
    // The standard errors times sqrt(n) are the standard deviations.
    const double n = std::sqrt(double(kPixels));
    const double covariance = meanAndError(ab).mean - meanA * meanB;
    return covariance / (meanAndError(a).error * n * meanAndError(b).error * n);
}

TEST(SampleTest, StreamsAreIndependent) {
    // The halves of a split gradient estimate need independent images: the first 16
    // points of the two streams give uncorrelated estimates (within 5 / sqrt(4096) of
    // 0), while the next 16 points of the same stream are anticorrelated with them,
    // which is what stratification does and what the streams are for.
    EXPECT_NEAR(estimateCorrelation(1u, 0u), 0.0, 5.0 / 64.0);
    EXPECT_LT(estimateCorrelation(0u, 16u), -5.0 / 64.0);
}

TEST(SampleTest, PureFunctionOfKey) {
    EXPECT_EQ(sample4(1u, 2u, 0u, 3u, 9u), sample4(1u, 2u, 0u, 3u, 9u));
    EXPECT_NE(sample4(1u, 2u, 0u, 3u, 9u), sample4(1u, 2u, 0u, 3u, 10u));
    EXPECT_NE(sample4(1u, 2u, 0u, 3u, 9u), sample4(1u, 2u, 0u, 4u, 9u));
    EXPECT_NE(sample4(1u, 2u, 0u, 3u, 9u), sample4(1u, 2u, 1u, 3u, 9u));
    EXPECT_NE(sample4(1u, 2u, 0u, 3u, 9u), sample4(2u, 2u, 0u, 3u, 9u));
    EXPECT_NE(sample4(1u, 2u, 0u, 3u, 9u), sample4(1u, 3u, 0u, 3u, 9u));
}

}  // namespace
}  // namespace vkdr::test
