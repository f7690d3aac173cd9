// Tracking through a density grid (shaders/lib/grid_tracking.glsl), compiled on the host:
// along a ray through a random grid, ratio tracking's transmittance is unbiased for
// exp(-sigma_t integral of d) in every channel, with a tight and with a loose majorant
// and with its Russian roulette at work; and delta tracking's collisions follow the
// distribution exp(-rate integral of d) sets, passing through with its probability, as
// the weights of defensive delta tracking's do.
// The reference integrals are quadratures of the trilinear density.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "host_density_grid.h"
#include "statistics.h"

namespace vkdr::test {
namespace {

constexpr float kVoxelsPerUnit = 10.0f;

// A random grid of 12 x 10 x 9 voxels, about a third of them 0, at index = 10 world,
// with majorant cells that bound its trilinear density times `looseness`.
HostDensityGrid randomGrid(float looseness) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> voxels;
    for (int i = 0; i < 12 * 10 * 9; ++i) voxels.push_back(unit(random) < 0.3f ? 0.0f : unit(random));
    return HostDensityGrid(ivec3(2, 1, 0), ivec3(12, 10, 9), std::move(voxels), kVoxelsPerUnit, looseness);
}

// randomGrid with its first 8 layers of voxels along x at 0, so that its majorant cells
// at the lowest x (index coordinates 1 to 9) are empty.
HostDensityGrid randomGridWithEmptyCells(float looseness) {
    HostDensityGrid dense = randomGrid(looseness);
    std::vector<float> voxels = dense.voxels;
    for (size_t i = 0; i < voxels.size(); ++i) {
        if (i % 12 < 8) voxels[i] = 0.0f;
    }
    return HostDensityGrid(ivec3(2, 1, 0), ivec3(12, 10, 9), std::move(voxels), kVoxelsPerUnit, looseness);
}

const vec3 kOrigin(0.05f, 0.02f, -0.1f);
const vec3 kEnd(1.55f, 1.15f, 1.0f);

// The integral of the density from the ray's origin to distance t, by the midpoint rule.
double densityIntegral(const HostDensityGrid& grid, double t) {
    const dvec3 direction = normalize(dvec3(kEnd - kOrigin));
    constexpr int kSteps = 20000;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) sum += grid.density(dvec3(kOrigin) + (i + 0.5) * t / kSteps * direction);
    return sum * t / kSteps;
}

void expectUnbiasedTransmittance(const HostDensityGrid& grid, vec3 sigma_t) {
    grid.bind();
    const vec3 direction = normalize(kEnd - kOrigin);
    const float length = glm::length(kEnd - kOrigin);
    const double integral = densityIntegral(grid, length);
    constexpr uint kRays = 40000;
    dvec3 sum(0.0), sumOfSquares(0.0);
    for (uint i = 0; i < kRays; ++i) {
        TrackingRandom random = trackingRandom(i, 0u, 0u, 0u, kTrackingShadow, 7u);
        uint stepsLeft = kMaxTransmittanceSteps;
        bool truncated = false;
        const dvec3 t = dvec3(ratioTrackTransmittance(grid.grid, kOrigin, direction, length, sigma_t, random,
                                                      stepsLeft, truncated));
        ASSERT_FALSE(truncated);
        sum += t;
        sumOfSquares += t * t;
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / kRays;
        const double standardError = std::sqrt((sumOfSquares[c] / kRays - mean * mean) / (kRays - 1));
        const double expected = std::exp(-double(sigma_t[c]) * integral);
        EXPECT_GT(standardError, 0.0);
        EXPECT_NEAR(mean, expected, 5.0 * standardError) << "channel " << c << ", optical depth "
                                                         << sigma_t[c] * integral;
    }
}

TEST(GridTracking, RatioTrackingIsUnbiasedWithATightMajorant) {
    expectUnbiasedTransmittance(randomGrid(1.0f), vec3(0.5f, 1.5f, 3.0f));
}

TEST(GridTracking, RatioTrackingIsUnbiasedWithALooseMajorant) {
    expectUnbiasedTransmittance(randomGrid(2.5f), vec3(0.5f, 1.5f, 3.0f));
}

// Transmittances down to about 0.004: the roulette below 0.05 ends most such estimates.
TEST(GridTracking, RatioTrackingIsUnbiasedThroughItsRoulette) {
    expectUnbiasedTransmittance(randomGrid(1.0f), vec3(2.0f, 4.0f, 8.0f));
}

// The running estimates at points along the walk (what an emission grid's points use):
// each unbiased for the transmittance to its own distance, the last at the walk's end,
// through the roulette as well.
TEST(GridTracking, RatioTrackingsRunningEstimatesAreUnbiasedAtEveryPoint) {
    const HostDensityGrid grid = randomGrid(1.5f);
    grid.bind();
    const vec3 direction = normalize(kEnd - kOrigin);
    const float length = glm::length(kEnd - kOrigin);
    const vec3 sigma_t(1.0f, 3.0f, 6.0f);
    const float fractions[kMaxTransmittancePoints] = {0.1f, 0.35f, 0.7f, 1.0f};
    constexpr uint kRays = 40000;
    dvec3 sum[kMaxTransmittancePoints] = {}, sumOfSquares[kMaxTransmittancePoints] = {};
    for (uint i = 0; i < kRays; ++i) {
        TrackingRandom random = trackingRandom(i, 0u, 0u, 0u, kTrackingEmission, 5u);
        uint stepsLeft = kMaxTransmittanceSteps;
        bool truncated = false;
        TransmittancePoints points;
        points.count = kMaxTransmittancePoints;
        for (uint k = 0; k < kMaxTransmittancePoints; ++k) points.t[k] = fractions[k] * length;
        ratioTrackTransmittanceAt(grid.grid, kOrigin, direction, length, sigma_t, random, stepsLeft, truncated,
                                  points);
        ASSERT_FALSE(truncated);
        for (uint k = 0; k < kMaxTransmittancePoints; ++k) {
            sum[k] += dvec3(points.transmittance[k]);
            sumOfSquares[k] += dvec3(points.transmittance[k]) * dvec3(points.transmittance[k]);
        }
    }
    for (uint k = 0; k < kMaxTransmittancePoints; ++k) {
        const double integral = densityIntegral(grid, fractions[k] * length);
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[k][c] / kRays;
            const double standardError = std::sqrt((sumOfSquares[k][c] / kRays - mean * mean) / (kRays - 1));
            EXPECT_GT(standardError, 0.0);
            EXPECT_NEAR(mean, std::exp(-double(sigma_t[c]) * integral), 5.0 * standardError)
                << "point " << k << ", channel " << c;
        }
    }
}

// The majorant's integral along a ray (which weighs a grid's emission estimates) against
// the midpoint rule over the cells, which errs by at most one step times the largest
// majorant at each face the ray crosses, no more than the cells along the three axes.
TEST(GridTracking, MajorantIntegralIsTheIntegralOverTheCellsTheRayCrosses) {
    const HostDensityGrid grid = randomGrid(1.5f);
    grid.bind();
    const vec3 direction = normalize(kEnd - kOrigin);
    for (float fraction : {0.4f, 1.0f, 3.0f}) {
        const float length = fraction * glm::length(kEnd - kOrigin);
        constexpr int kSteps = 20000;
        const double step = double(length) / kSteps;
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i) sum += grid.majorant(dvec3(kOrigin) + (i + 0.5) * step * dvec3(direction));
        const double largest = *std::max_element(grid.majorants.begin(), grid.majorants.end());
        const ivec3 cells = ivec3(grid.grid.majorantCells);
        const double integral = majorantIntegral(grid.grid, gridRay(grid.grid, kOrigin, direction), length);
        EXPECT_NEAR(integral, sum * step, (cells.x + cells.y + cells.z) * step * largest) << "length " << length;
        EXPECT_GE(integral, densityIntegral(grid, length)) << "length " << length;
    }
}

constexpr float kFlightRate = 2.0f;
constexpr int kBins = 10;
constexpr uint kFlights = 1u << 17;

// kFlights free flights along the test ray through `grid` at kFlightRate, each handed to
// `visit` with the bin it ends in: the tenth of the ray where it collided, or kBins where
// it passed through.
template <typename Visit>
void trackFlights(const HostDensityGrid& grid, float defensiveDensity, Visit&& visit) {
    grid.bind();
    const vec3 direction = normalize(kEnd - kOrigin);
    const float length = glm::length(kEnd - kOrigin);
    for (uint i = 0; i < kFlights; ++i) {
        TrackingRandom random = trackingRandom(i, 0u, 0u, 0u, kTrackingFreeFlight, 3u);
        const vec4 first = nextTrackingRandom(random);
        const GridFreeFlight flight =
            trackFreeFlight(grid.grid, kOrigin, direction, length, kFlightRate, vec2(first), defensiveDensity, random);
        ASSERT_FALSE(flight.paused);
        visit(flight, flight.collided ? size_t(std::min(kBins - 1, int(flight.t / length * kBins))) : size_t(kBins));
    }
}

// The probability of ending in each of trackFlights' bins that the density sets.
std::vector<double> binProbabilities(const HostDensityGrid& grid) {
    const float length = glm::length(kEnd - kOrigin);
    auto survival = [&](double t) { return std::exp(-double(kFlightRate) * densityIntegral(grid, t)); };
    std::vector<double> probabilities(kBins + 1);
    for (int b = 0; b < kBins; ++b) {
        probabilities[size_t(b)] = survival(length * b / kBins) - survival(length * (b + 1) / kBins);
    }
    probabilities[kBins] = survival(length);
    return probabilities;
}

TEST(GridTracking, DeltaTrackingCollidesAsTheDensitySays) {
    const HostDensityGrid grid = randomGrid(1.5f);
    std::vector<double> counts(kBins + 1, 0.0);
    trackFlights(grid, 0.0f, [&](const GridFreeFlight&, size_t bin) { counts[bin] += 1.0; });
    std::vector<double> expected = binProbabilities(grid);
    for (double& e : expected) e *= kFlights;
    int dof = 0;
    const double statistic = chiSquare(counts, expected, &dof);
    EXPECT_LT(statistic, chiSquareCritical(dof));
}

// Defensive delta tracking (a gradient pass that differentiates the density) collides
// where the density is 0 too, in empty majorant cells as well, and its weights restore
// the same distribution: the mean weight in each bin, the flights that pass through
// included, is the probability the density sets, within 5 standard errors of the
// weights' own spread.
TEST(GridTracking, DefensiveDeltaTrackingWeighsToTheDensitysDistribution) {
    const HostDensityGrid grid = randomGridWithEmptyCells(1.5f);
    // As the renderer sets it: kDefensiveCollisionsPerCrossing / (the diagonal of the box
    // the density reaches times the largest rate).
    const double diagonal = glm::length(dvec3(ivec3(grid.grid.size) + 1)) / kVoxelsPerUnit;
    const float defensiveDensity = float(kDefensiveCollisionsPerCrossing / (diagonal * kFlightRate));
    const vec3 direction = normalize(kEnd - kOrigin);
    std::vector<double> sums(kBins + 1, 0.0), sumsOfSquares(kBins + 1, 0.0);
    uint emptyCellCollisions = 0;  // none unless empty cells are walked with a raised majorant
    trackFlights(grid, defensiveDensity, [&](const GridFreeFlight& flight, size_t bin) {
        double weight = flight.nullWeight;
        if (flight.collided) {
            weight *= flight.density / flight.chance;
            const float x = (kOrigin + flight.t * direction).x * kVoxelsPerUnit;
            emptyCellCollisions += x >= 1.0f && x < 9.0f ? 1u : 0u;
        }
        sums[bin] += weight;
        sumsOfSquares[bin] += weight * weight;
    });
    EXPECT_GT(emptyCellCollisions, 0u);
    const std::vector<double> expected = binProbabilities(grid);
    for (int b = 0; b <= kBins; ++b) {
        const double mean = sums[size_t(b)] / kFlights;
        const double error = std::sqrt((sumsOfSquares[size_t(b)] / kFlights - mean * mean) / (kFlights - 1));
        // 1e-6 covers the quadrature's own error, where a bin outside the grid has no spread.
        EXPECT_NEAR(mean, expected[size_t(b)], 5.0 * error + 1e-6) << "bin " << b;
    }
}

}  // namespace
}  // namespace vkdr::test
