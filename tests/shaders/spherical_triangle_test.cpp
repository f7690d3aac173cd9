// Sampling directions uniformly in a triangle's solid angle
// (shaders/lib/spherical_triangle.glsl): the solid angle against closed forms and
// against quadrature of cos / r^2 over the triangle; the sampled directions land in the
// triangle, spread over its sub-triangles in proportion to their solid angles
// (chi-square), and average to Lambert's vector irradiance, for a lamp 2e5 wide too.
#include <gtest/gtest.h>

#include <array>

#include "glsl_host.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

using namespace glsl;
using DVec3 = glm::dvec3;

struct TriangleCase {
    const char* label;
    vec3 v0, v1, v2;  // seen from the origin
};

void PrintTo(const TriangleCase& c, std::ostream* os) {
    *os << c.label;
}

// The solid angle as the integral of cos / r^2 over the triangle: the midpoint rule on
// its regular subdivision into n^2 triangles, in double precision.
double solidAngleByQuadrature(const TriangleCase& c) {
    constexpr int n = 1024;
    const DVec3 p0(c.v0), e1 = DVec3(c.v1) - p0, e2 = DVec3(c.v2) - p0;
    const DVec3 normal = glm::cross(e1, e2);
    const double cellArea = 0.5 * glm::length(normal) / (double(n) * n);
    const DVec3 unitNormal = glm::normalize(normal);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; i + j < n; ++j) {
            for (int upper = 0; upper < (i + j < n - 1 ? 2 : 1); ++upper) {
                // The centroid of the cell's lower or upper triangle.
                const double b1 = (i + (upper ? 2.0 / 3.0 : 1.0 / 3.0)) / n;
                const double b2 = (j + (upper ? 2.0 / 3.0 : 1.0 / 3.0)) / n;
                const DVec3 x = p0 + b1 * e1 + b2 * e2;
                const double r = glm::length(x);
                sum += std::abs(glm::dot(unitNormal, x)) / (r * r * r) * cellArea;
            }
        }
    }
    return sum;
}

double solidAngleInDouble(DVec3 a, DVec3 b, DVec3 c) {
    a = glm::normalize(a);
    b = glm::normalize(b);
    c = glm::normalize(c);
    return 2.0 * std::atan2(std::abs(glm::dot(a, glm::cross(b, c))), 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
}

float solidAngleOf(const TriangleCase& c) {
    return sphericalTriangleArea(normalize(c.v0), normalize(c.v1), normalize(c.v2));
}

TEST(SphericalTriangleTest, SolidAngleMatchesClosedForms) {
    // An octant: an eighth of the sphere.
    EXPECT_NEAR(sphericalTriangleArea(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)), kPi / 2.0f, 1e-6f);
    // Half of a square of side 2 at distance 1, which subtends 4 asin(1/2).
    EXPECT_NEAR(sphericalTriangleArea(normalize(vec3(-1, -1, 1)), normalize(vec3(1, -1, 1)), normalize(vec3(1, 1, 1))),
                kPi / 3.0f, 1e-6f);
    // The orientation does not matter.
    EXPECT_NEAR(sphericalTriangleArea(vec3(0, 0, 1), vec3(0, 1, 0), vec3(1, 0, 0)), kPi / 2.0f, 1e-6f);
}

class SphericalTriangleSampling : public ::testing::TestWithParam<TriangleCase> {};

TEST_P(SphericalTriangleSampling, SolidAngleMatchesQuadrature) {
    const TriangleCase& c = GetParam();
    const double quadrature = solidAngleByQuadrature(c);
    EXPECT_NEAR(solidAngleOf(c), quadrature, 1e-4 * quadrature) << "quadrature " << quadrature;
}

// The bin of a point with barycentrics (b1, b2) among the n^2 triangles of the regular
// subdivision; -1 outside the triangle.
int subTriangle(double b1, double b2, int n) {
    if (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0) {
        return -1;
    }
    const int i = std::min(int(b1 * n), n - 1);
    const int j = std::min(int(b2 * n), n - 1 - i);
    const bool upper = b1 * n - i + b2 * n - j > 1.0 && i + j < n - 1;
    return 2 * (i * n + j) + (upper ? 1 : 0);
}

// Every sampled direction meets the triangle (up to rounding at its edges), and the
// counts in its sub-triangles follow their solid angles.
void expectDirectionsUniformInSolidAngle(const TriangleCase& c) {
    constexpr int n = 6;
    constexpr uint kSamples = 1u << 18;
    const DVec3 p0(c.v0), e1 = DVec3(c.v1) - p0, e2 = DVec3(c.v2) - p0;
    std::vector<double> counts(2 * n * n, 0.0), expected(2 * n * n, 0.0);
    const double total = solidAngleInDouble(c.v0, c.v1, c.v2);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; i + j < n; ++j) {
            auto corner = [&](double a, double b) { return p0 + (a / n) * e1 + (b / n) * e2; };
            expected[2 * (i * n + j)] =
                kSamples * solidAngleInDouble(corner(i, j), corner(i + 1, j), corner(i, j + 1)) / total;
            if (i + j < n - 1) {
                expected[2 * (i * n + j) + 1] =
                    kSamples * solidAngleInDouble(corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)) / total;
            }
        }
    }
    const vec3 a = normalize(c.v0), b = normalize(c.v1), cc = normalize(c.v2);
    const float area = sphericalTriangleArea(a, b, cc);
    int outside = 0;
    for (uint s = 0; s < kSamples; ++s) {
        const vec4 u = sample4(11u, s, 0u, kDimLight, 5u);
        const DVec3 d(sampleSphericalTriangle(a, b, cc, area, vec2(u.y, u.z)));
        ASSERT_NEAR(glm::length(d), 1.0, 1e-5);
        // Where the direction meets the triangle's plane: p0 + b1 e1 + b2 e2 = t d.
        const glm::dmat3 system(e1, e2, -d);
        const DVec3 solution = glm::inverse(system) * (-p0);
        const int bin = subTriangle(solution.x, solution.y, n);
        if (bin < 0) {
            // Within rounding of an edge counts as on it.
            ASSERT_GT(std::min({solution.x, solution.y, 1.0 - solution.x - solution.y}), -1e-4) << "sample " << s;
            ++outside;
            continue;
        }
        ASSERT_GT(solution.z, 0.0) << "sample " << s;
        counts[bin] += 1.0;
    }
    EXPECT_LT(outside, int(kSamples / 1000));
    int dof;
    const double x2 = chiSquare(counts, expected, &dof);
    EXPECT_LT(x2, chiSquareCritical(dof)) << "dof " << dof;
}

TEST_P(SphericalTriangleSampling, DirectionsAreUniformInSolidAngle) {
    expectDirectionsUniformInSolidAngle(GetParam());
}

// Lambert's closed form for the integral of the direction over a polygon's solid angle
// seen from the origin (its vector irradiance at unit radiance): half the sum over its
// edges of the angle an edge subtends times the unit normal of the plane through the
// edge and the origin, up to a sign that the winding sets.
DVec3 vectorIrradiance(const TriangleCase& c) {
    const std::array<DVec3, 3> v = {DVec3(c.v0), DVec3(c.v1), DVec3(c.v2)};
    DVec3 sum(0.0);
    for (int i = 0; i < 3; ++i) {
        const DVec3 a = glm::normalize(v[i]), b = glm::normalize(v[(i + 1) % 3]);
        const DVec3 normal = glm::cross(a, b);
        sum += 0.5 * std::atan2(glm::length(normal), glm::dot(a, b)) * glm::normalize(normal);
    }
    // Towards the triangle, whichever its winding.
    return glm::dot(sum, v[0]) < 0.0 ? -sum : sum;
}

// The mean sampled direction times the solid angle is the integral of the direction
// over the triangle's solid angle: Lambert's vector irradiance, within 5 standard
// errors of the independent-sample estimate (the stratified points do better).
void expectMeanDirectionMatchesLambert(const TriangleCase& c) {
    constexpr uint kSamples = 1u << 18;
    const vec3 a = normalize(c.v0), b = normalize(c.v1), cc = normalize(c.v2);
    const float area = sphericalTriangleArea(a, b, cc);
    DVec3 sum(0.0), sumSquares(0.0);
    for (uint s = 0; s < kSamples; ++s) {
        const vec4 u = sample4(13u, s, 0u, kDimLight, 7u);
        const DVec3 d = DVec3(sampleSphericalTriangle(a, b, cc, area, vec2(u.y, u.z))) * double(area);
        sum += d;
        sumSquares += d * d;
    }
    const DVec3 mean = sum / double(kSamples);
    const DVec3 expected = vectorIrradiance(c);
    for (int k = 0; k < 3; ++k) {
        const double standardError = std::sqrt(std::max(sumSquares[k] / kSamples - mean[k] * mean[k], 0.0) / kSamples);
        EXPECT_NEAR(mean[k], expected[k], 5.0 * standardError + 1e-6) << "component " << k;
    }
}

TEST_P(SphericalTriangleSampling, MeanDirectionMatchesLambertsFormula) {
    expectMeanDirectionMatchesLambert(GetParam());
}

// Triangles too vast for the quadrature and the binning: the halves of a lamp 2e5 wide,
// 1 above the viewer. In the far half two corners are nearly opposite each other.
class VastTriangleSampling : public ::testing::TestWithParam<TriangleCase> {};

TEST_P(VastTriangleSampling, MeanDirectionMatchesLambertsFormula) {
    expectMeanDirectionMatchesLambert(GetParam());
}

constexpr float kVast = 1.0e5f;
const vec3 kViewer(0.07f, 0.03f, 0.0f);

INSTANTIATE_TEST_SUITE_P(
    LampHalves, VastTriangleSampling,
    ::testing::Values(TriangleCase{"NearHalf", vec3(-kVast, -kVast, 1.0f) - kViewer, vec3(kVast, -kVast, 1.0f) - kViewer,
                                   vec3(kVast, kVast, 1.0f) - kViewer},
                      TriangleCase{"FarHalf", vec3(-kVast, -kVast, 1.0f) - kViewer, vec3(kVast, kVast, 1.0f) - kViewer,
                                   vec3(-kVast, kVast, 1.0f) - kViewer}),
    [](const ::testing::TestParamInfo<TriangleCase>& info) { return info.param.label; });

INSTANTIATE_TEST_SUITE_P(
    Triangles, SphericalTriangleSampling,
    ::testing::Values(TriangleCase{"Octant", vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)},
                      TriangleCase{"AboveTheViewer", vec3(-0.5f, -0.4f, 1.0f), vec3(0.7f, -0.3f, 1.2f), vec3(0.1f, 0.6f, 0.9f)},
                      TriangleCase{"CloseAndObtuse", vec3(-2.0f, 0.05f, 0.3f), vec3(2.0f, -0.1f, 0.3f), vec3(0.1f, 0.4f, 0.35f)},
                      TriangleCase{"Wide", vec3(-6.0f, -5.0f, 1.0f), vec3(7.0f, -4.0f, 1.0f), vec3(0.0f, 8.0f, 1.0f)},
                      TriangleCase{"AtTheThreshold", vec3(2.675f, 1.7f, 4.9f), vec3(3.8f, 1.95f, 4.9f), vec3(3.175f, 2.95f, 5.4f)}),
    [](const ::testing::TestParamInfo<TriangleCase>& info) { return info.param.label; });

TEST(SphericalTriangleTest, TheCasesSpanTheRangeSampledBySolidAngle) {
    const float threshold = solidAngleOf({"", vec3(2.675f, 1.7f, 4.9f), vec3(3.8f, 1.95f, 4.9f), vec3(3.175f, 2.95f, 5.4f)});
    EXPECT_TRUE(samplesBySolidAngle(threshold));
    EXPECT_LT(threshold, 1.5f * kMinSphericalSamplingArea);
    EXPECT_FALSE(samplesBySolidAngle(0.5f * kMinSphericalSamplingArea));
    EXPECT_FALSE(samplesBySolidAngle(2.0f * kPi));
}

}  // namespace
}  // namespace vkdr::test
