// Henyey-Greenstein sampling, evaluation and derivative (shaders/lib/phase_hg.glsl) over
// the whole accepted range of g, its ends and g near 0 included: the float code agrees
// with the formulas evaluated in long double, the pdf integrates to one, sampled
// cosines follow the pdf (chi-square over equal-probability bins, and the first two
// moments), d log p / d g matches a central difference, and nothing is NaN or infinite,
// even for directions exactly forward, exactly backward or a rounding beyond.
#include <gtest/gtest.h>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;
using Real = long double;

constexpr float kMaxAbsG = 0.99f;  // the accepted range of g (scene/parameter_kinds.cpp)

Real hgPdfReference(Real mu, Real g) {
    Real d = 1 + g * g - 2 * g * mu;
    return (1 - g * g) / (4 * M_PIl * d * std::sqrt(d));
}

Real hgLogPdfReference(Real mu, Real g) {
    return std::log(hgPdfReference(mu, g));
}

// P(cosine <= mu), the closed-form CDF of the cosine.
Real hgCdfReference(Real mu, Real g) {
    if (g == 0) {
        return (mu + 1) / 2;
    }
    return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
}

// Its inverse, the textbook form: long double keeps digits to spare down to |g| ~ 1e-9.
Real hgInverseCdfReference(Real u, Real g) {
    if (g == 0) {
        return 2 * u - 1;
    }
    Real s = (1 - g * g) / (1 - g + 2 * g * u);
    return std::clamp((1 + g * g - s * s) / (2 * g), Real(-1), Real(1));
}

// Cosines at which everything is checked: both poles exactly, the floats beside them,
// a rounding beyond them (as a dot product of unit vectors can give), and between.
std::vector<float> testCosines() {
    std::vector<float> mus = {-1.0f, 1.0f, std::nextafter(1.0f, 0.0f), std::nextafter(-1.0f, 0.0f),
                              std::nextafter(1.0f, 2.0f), std::nextafter(-1.0f, -2.0f)};
    for (int i = 0; i <= 40; ++i) {
        mus.push_back(-1.0f + 2.0f * float(i) / 40.0f);
    }
    for (float e : {1e-6f, 1e-4f, 1e-2f}) {
        mus.push_back(1.0f - e);
        mus.push_back(-1.0f + e);
    }
    return mus;
}

class HgTest : public ::testing::TestWithParam<float> {};

TEST_P(HgTest, PdfMatchesTheFormulaAndIsFinite) {
    const float g = GetParam();
    for (float mu : testCosines()) {
        float p = hgPhase(mu, g);
        Real expected = hgPdfReference(std::clamp(Real(mu), Real(-1), Real(1)), g);
        ASSERT_TRUE(std::isfinite(p)) << "mu " << mu;
        EXPECT_NEAR(p, double(expected), 1e-5 * double(expected)) << "mu " << mu;
    }
}

TEST_P(HgTest, PdfIntegratesToOne) {
    const float g = GetParam();
    // Midpoint rule in the angle, where the peak of |g| = 0.99 (about 0.01 wide) spans
    // hundreds of steps; the rule's error is then far below float rounding.
    constexpr int kSteps = 400000;
    const double h = M_PI / kSteps;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        double theta = (i + 0.5) * h;
        sum += double(hgPhase(float(std::cos(theta)), g)) * std::sin(theta);
    }
    EXPECT_NEAR(sum * h * 2.0 * M_PI, 1.0, 1e-5);
}

TEST_P(HgTest, LogDerivativeMatchesCentralDifference) {
    const float g = GetParam();
    const Real h = 1e-7L;
    for (float mu : testCosines()) {
        Real m = std::clamp(Real(mu), Real(-1), Real(1));
        Real fd = (hgLogPdfReference(m, g + h) - hgLogPdfReference(m, g - h)) / (2 * h);
        // The sum of two terms that may cancel: float rounding is relative to their sizes.
        Real d = 1 + Real(g) * g - 2 * Real(g) * m;
        double scale = double(2 * std::abs(Real(g)) / (1 - Real(g) * g) + 3 * std::abs(m - g) / d);
        float derivative = hgPhaseDLogG(mu, g);
        ASSERT_TRUE(std::isfinite(derivative)) << "mu " << mu;
        EXPECT_NEAR(derivative, double(fd), 1e-5 * std::max(1.0, scale)) << "mu " << mu;
    }
}

TEST_P(HgTest, SamplerInvertsTheCdfToFloatPrecision) {
    const float g = GetParam();
    for (int i = 0; i <= 1 << 16; ++i) {
        float u = std::min(float(i) / float(1 << 16), std::nextafter(1.0f, 0.0f));
        float mu = sampleHgCosine(u, g);
        ASSERT_TRUE(std::isfinite(mu)) << "u " << u;
        // A few roundings of terms up to 2 in size; where mu rises steeply with u (the
        // far side of a peaked lobe) that is all the precision a float map can have.
        EXPECT_NEAR(mu, double(hgInverseCdfReference(u, g)), 1e-6) << "u " << u;
    }
    EXPECT_EQ(sampleHgCosine(0.0f, g), -1.0f);
}

TEST_P(HgTest, SampledCosinesFollowThePdf) {
    const float g = GetParam();
    constexpr int kBins = 32;
    constexpr uint kSamples = 1u << 20;
    // Bins of equal probability, found through the CDF in long double, so the peak of
    // |g| = 0.99 is resolved as finely as the rest.
    std::vector<double> counts(kBins, 0.0), expected(kBins, double(kSamples) / kBins);
    double sum = 0.0, sumSquares = 0.0, sumP2 = 0.0, sumP2Squares = 0.0;
    const vec3 incoming = normalize(vec3(0.3f, -0.5f, 0.8f));
    for (uint i = 0; i < kSamples; ++i) {
        vec4 u = sample4(i, 0u, 0u, kDimScatter, 3u);
        vec3 w = sampleHg(incoming, g, vec2(u.x, u.y));
        ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z));
        ASSERT_NEAR(length(w), 1.0f, 1e-5f);
        float mu = sampleHgCosine(u.x, g);
        ASSERT_NEAR(dot(incoming, w), mu, 1e-6f);
        double cdf = double(hgCdfReference(mu, g));
        counts[std::clamp(int(cdf * kBins), 0, kBins - 1)] += 1.0;
        double p2 = 1.5 * double(mu) * mu - 0.5;
        sum += mu;
        sumSquares += double(mu) * mu;
        sumP2 += p2;
        sumP2Squares += p2 * p2;
    }
    int dof;
    double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof));
    // HG's Legendre moments are E[P_l(mu)] = g^l; each mean is held to 5 standard errors.
    const double n = kSamples;
    double mean = sum / n, meanP2 = sumP2 / n;
    double error = std::sqrt((sumSquares / n - mean * mean) / n);
    double errorP2 = std::sqrt((sumP2Squares / n - meanP2 * meanP2) / n);
    EXPECT_NEAR(mean, g, 5.0 * error);
    EXPECT_NEAR(meanP2, double(g) * g, 5.0 * errorP2);
}

INSTANTIATE_TEST_SUITE_P(AcceptedRange, HgTest,
                         ::testing::Values(-kMaxAbsG, -0.9f, -0.4f, -1e-3f, -1e-6f, 0.0f, 1e-7f, 5e-4f, 2e-3f, 0.3f,
                                           0.8f, 0.95f, kMaxAbsG));

}  // namespace
}  // namespace vkdr::test
