// Free-flight sampling with spectral MIS and transmittance (shaders/lib/medium.glsl):
// sampled distances follow freeFlightPdf, survival is the probability of passing t,
// and the surface-weighted estimator T / survival is unbiased for each channel. The
// emission a segment gathers, and its sigma_t derivative, against the closed forms in
// double precision, on both sides of the switch to their series and to infinity.
#include <gtest/gtest.h>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;

const vec3 kSigmaT(0.5f, 1.5f, 4.0f);

TEST(MediumTest, SampledDistancesFollowTheMixturePdf) {
    constexpr int kBins = 50;
    constexpr float kMaxT = 5.0f;
    constexpr uint kSamples = 1u << 19;
    std::vector<double> counts(kBins + 1, 0.0), expected(kBins + 1, 0.0);
    for (uint i = 0; i < kSamples; ++i) {
        vec4 u = sample4(i, 1u, 0u, 2u * kDimGroupsPerSegment + kDimFreeFlight, 0u);
        float t = sampleFreeFlight(kSigmaT, vec2(u.x, u.y));
        counts[t >= kMaxT ? kBins : int(t / kMaxT * kBins)] += 1.0;
    }
    for (int b = 0; b < kBins; ++b) {
        float t0 = kMaxT * b / kBins, t1 = kMaxT * (b + 1) / kBins;
        expected[b] = kSamples * (freeFlightSurvival(kSigmaT, t0) - freeFlightSurvival(kSigmaT, t1));
    }
    expected[kBins] = kSamples * freeFlightSurvival(kSigmaT, kMaxT);
    int dof;
    double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof));
}

TEST(MediumTest, PdfIsMinusTheDerivativeOfSurvival) {
    for (float t : {0.0f, 0.1f, 0.7f, 2.0f}) {
        const float h = 1e-3f;
        float derivative = (freeFlightSurvival(kSigmaT, t + h) - freeFlightSurvival(kSigmaT, t - h)) / (2.0f * h);
        EXPECT_NEAR(freeFlightPdf(kSigmaT, t), -derivative, 1e-3f);
    }
}

TEST(MediumTest, TransmittanceIsBeerLambert) {
    vec3 tr = transmittance(kSigmaT, 0.8f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(tr[c], std::exp(-kSigmaT[c] * 0.8f));
    }
}

TEST(MediumTest, EmptyChannelNeverStopsTheRay) {
    const vec3 sigma(0.0f, 2.0f, 0.0f);
    for (uint i = 0; i < 1000; ++i) {
        vec4 u = sample4(i, 0u, 0u, kDimFreeFlight, 0u);
        float t = sampleFreeFlight(sigma, vec2(u.x, u.y));
        if (int(u.x * 3.0f) != 1) {
            EXPECT_EQ(t, kFar);
        }
    }
    EXPECT_FLOAT_EQ(freeFlightSurvival(sigma, kFar), 2.0f / 3.0f);
}

TEST(MediumTest, EmissionAlongASegmentMatchesItsClosedFormAndDerivative) {
    for (double s : {1e-3, 0.02, 0.5, 3.0, 40.0}) {
        for (double sigma : {0.0, 1e-4, 0.0199, 0.0201, 0.7, 5.0, 9.0}) {
            const SegmentEmission e = emissionAlongSegment(vec3(float(sigma)), float(s));
            const double x = sigma * s;
            const double value = sigma > 0.0 ? -std::expm1(-x) / sigma : s;
            // d/dsigma of (1 - exp(-sigma s)) / sigma; -s^2 / 2 at sigma = 0.
            const double derivative =
                sigma > 0.0 ? (s * std::exp(-x) + std::expm1(-x) / sigma) / sigma : -0.5 * s * s;
            EXPECT_NEAR(e.value.x, value, 2e-6 * value) << "s " << s << " sigma " << sigma;
            EXPECT_NEAR(e.dSigmaT.x, derivative, 2e-5 * std::abs(derivative) + 1e-12) << "s " << s << " sigma " << sigma;
        }
    }
    const SegmentEmission unbounded = emissionAlongSegment(vec3(0.5f, 2.0f, 8.0f), kFar);
    for (int c = 0; c < 3; ++c) {
        const float sigma = vec3(0.5f, 2.0f, 8.0f)[c];
        EXPECT_FLOAT_EQ(unbounded.value[c], 1.0f / sigma);
        EXPECT_FLOAT_EQ(unbounded.dSigmaT[c], -1.0f / (sigma * sigma));
    }
}

}  // namespace
}  // namespace vkdr::test
