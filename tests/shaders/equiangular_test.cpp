// Equiangular distance sampling (shaders/lib/equiangular.glsl): the sampled distances
// follow equiangularPdf, whose integral over each bin comes from Simpson's rule, for a
// light beside, ahead of, behind and beyond the segment, and on an unbounded segment;
// the density integrates to one, and is zero outside the segment; a light on the ray's
// line is refused everywhere.
#include <gtest/gtest.h>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;

// The integral of the density over [t0, t1) by composite Simpson's rule, in double
// precision on the float density; the last node is the float below t1, as the segment's
// end is not in it.
double integratePdf(const EquiangularSegment& s, double t0, double t1) {
    constexpr int kIntervals = 4000;  // resolves the sharpest peak here (0.01 wide) with 40 nodes
    const double h = (t1 - t0) / kIntervals;
    double sum = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
        const double weight = i == 0 || i == kIntervals ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        const float t = i == kIntervals ? std::nextafter(float(t1), float(t0)) : float(t0 + i * h);
        sum += weight * equiangularPdf(s, t);
    }
    return sum * h / 3.0;
}

struct SegmentCase {
    const char* label;
    vec3 lightPoint;
    float tMax;
    float histogramEnd;  // the bins cover [0, histogramEnd); the rest is one more bin
};

void PrintTo(const SegmentCase& c, std::ostream* os) {
    *os << c.label;
}

class EquiangularTest : public ::testing::TestWithParam<SegmentCase> {};

const vec3 kOrigin(0.5f, -1.0f, 2.0f);
const vec3 kDirection = normalize(vec3(1.0f, 2.0f, -0.5f));

TEST_P(EquiangularTest, SampledDistancesFollowThePdf) {
    const SegmentCase& c = GetParam();
    const EquiangularSegment s = equiangularSegment(kOrigin, kDirection, c.tMax, c.lightPoint);
    ASSERT_TRUE(s.valid);
    constexpr int kBins = 64;
    constexpr uint kSamples = 1u << 18;
    std::vector<double> counts(kBins + 1, 0.0), expected(kBins + 1, 0.0);
    for (uint i = 0; i < kSamples; ++i) {
        const float t = sampleEquiangular(s, sample4(7u, i, 0u, kDimEquiangular, 3u).w);
        ASSERT_GE(t, 0.0f);
        ASSERT_LT(t, c.tMax);
        counts[t >= c.histogramEnd ? kBins : int(t / c.histogramEnd * kBins)] += 1.0;
    }
    double inBins = 0.0;
    for (int b = 0; b < kBins; ++b) {
        expected[b] = kSamples * integratePdf(s, double(c.histogramEnd) * b / kBins,
                                              double(c.histogramEnd) * (b + 1) / kBins);
        inBins += expected[b];
    }
    expected[kBins] = kSamples - inBins;
    int dof;
    const double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof));
}

// Simpson's rule on pieces split at the density's peak, where it is sharpest, each ten
// times as long as the one before from there. An unbounded segment is integrated to 10^4, beyond which
// its density's mass is below 3e-5 here.
TEST_P(EquiangularTest, PdfIntegratesToOne) {
    const SegmentCase& c = GetParam();
    const EquiangularSegment s = equiangularSegment(kOrigin, kDirection, c.tMax, c.lightPoint);
    const double end = std::min(double(c.tMax), 1e4);
    const double peak = std::clamp(double(s.closest), 0.0, end);
    double integral = integratePdf(s, 0.0, peak);
    for (double from = peak; from < end; from = std::max(10.0, 10.0 * from)) {
        integral += integratePdf(s, from, std::min(end, std::max(10.0, 10.0 * from)));
    }
    EXPECT_NEAR(integral, 1.0, 1e-4);
    EXPECT_EQ(equiangularPdf(s, -1e-3f), 0.0f);
    if (c.tMax < kFar) {
        EXPECT_EQ(equiangularPdf(s, c.tMax), 0.0f);
    }
}

// The point nearest to the light at t = 2 along the ray, 0.3 away from it; and so on.
vec3 besideTheRay(float t, float height) {
    return kOrigin + t * kDirection + height * normalize(cross(kDirection, vec3(0.0f, 0.0f, 1.0f)));
}

INSTANTIATE_TEST_SUITE_P(Lights, EquiangularTest,
                         ::testing::Values(SegmentCase{"Beside", besideTheRay(2.0f, 0.3f), 5.0f, 5.0f},
                                           SegmentCase{"Close", besideTheRay(1.0f, 0.01f), 3.0f, 3.0f},
                                           SegmentCase{"Behind", besideTheRay(-1.5f, 0.5f), 4.0f, 4.0f},
                                           SegmentCase{"Beyond", besideTheRay(6.0f, 1.0f), 2.0f, 2.0f},
                                           SegmentCase{"Unbounded", besideTheRay(2.0f, 0.5f), kFar, 20.0f}),
                         [](const ::testing::TestParamInfo<SegmentCase>& info) { return info.param.label; });

TEST(EquiangularSegmentTest, ALightOnTheRaysLineIsRefused) {
    const EquiangularSegment s = equiangularSegment(kOrigin, kDirection, 5.0f, kOrigin + 2.0f * kDirection);
    EXPECT_FALSE(s.valid);
    EXPECT_EQ(equiangularPdf(s, 2.0f), 0.0f);
    EXPECT_EQ(equiangularPdf(s, 1.0f), 0.0f);
}

}  // namespace
}  // namespace vkdr::test
