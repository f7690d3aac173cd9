// Henyey-Greenstein sampling and derivative (shaders/lib/phase_hg.glsl): sampled
// cosines follow the pdf (chi-square), the pdf integrates to one over the sphere, and
// d log p / d g matches a central difference.
#include <gtest/gtest.h>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;

// Probability of mu in [a, b] under HG: the closed-form CDF of the cosine.
double hgCosineProbability(double a, double b, double g) {
    if (std::abs(g) < 1e-3) {
        return (b - a) / 2.0;
    }
    auto cdf = [g](double mu) {
        return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
    };
    return cdf(b) - cdf(a);
}

class HgSamplingTest : public ::testing::TestWithParam<float> {};

TEST_P(HgSamplingTest, SampledCosinesFollowThePdf) {
    const float g = GetParam();
    constexpr int kBins = 64;
    constexpr uint kSamples = 1u << 19;
    std::vector<double> counts(kBins, 0.0), expected(kBins, 0.0);
    const vec3 incoming = normalize(vec3(0.3f, -0.5f, 0.8f));
    for (uint i = 0; i < kSamples; ++i) {
        vec4 u = uniform4(i, 0u, 0u, kDimScatter, 3u);
        vec3 w = sampleHg(incoming, g, vec2(u.x, u.y));
        ASSERT_NEAR(length(w), 1.0f, 1e-5f);
        float mu = clamp(dot(incoming, w), -1.0f, 1.0f);
        counts[std::min(kBins - 1, int((mu + 1.0f) * 0.5f * kBins))] += 1.0;
    }
    for (int b = 0; b < kBins; ++b) {
        expected[b] = kSamples * hgCosineProbability(-1.0 + 2.0 * b / kBins, -1.0 + 2.0 * (b + 1) / kBins, g);
    }
    int dof;
    double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof)) << "g = " << g;
}

TEST_P(HgSamplingTest, PdfIntegratesToOne) {
    const float g = GetParam();
    // Midpoint rule in mu; the azimuth contributes 2 pi.
    constexpr int kSteps = 200000;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        float mu = -1.0f + (i + 0.5f) * 2.0f / kSteps;
        sum += hgPhase(mu, g);
    }
    EXPECT_NEAR(sum * 2.0 / kSteps * 2.0 * kPi, 1.0, 2e-3);
}

TEST_P(HgSamplingTest, LogDerivativeMatchesCentralDifference) {
    const float g = GetParam();
    const double h = 1e-3;
    for (float mu : {-0.9f, -0.3f, 0.0f, 0.4f, 0.95f}) {
        auto logP = [mu](double gg) {
            double d = 1.0 + gg * gg - 2.0 * gg * mu;
            return std::log((1.0 - gg * gg) / (4.0 * M_PI * d * std::sqrt(d)));
        };
        double fd = (logP(g + h) - logP(g - h)) / (2.0 * h);
        EXPECT_NEAR(hgPhaseDLogG(mu, g), fd, 1e-3 * std::max(1.0, std::abs(fd))) << "mu " << mu;
    }
}

INSTANTIATE_TEST_SUITE_P(Anisotropies, HgSamplingTest, ::testing::Values(-0.9f, -0.4f, 0.0f, 0.0005f, 0.3f, 0.8f, 0.95f));

}  // namespace
}  // namespace vkdr::test
