// Two estimators of a shadow ray's transmittance gradient with respect to every voxel of
// a density grid, dT/d(voxel v) = -sigma_t T integral of w_v (w_v the voxel's trilinear
// weight along the ray), compared on rays through a procedural plume:
// - the renderer's (shaders/lib/grid_adjoint.glsl): ratio tracking's estimate of T times
//   -sigma_t times the estimate of the integral from kDensityIntegralPoints stratified
//   points with random numbers of their own;
// - differential ratio tracking (Nimier-David et al. 2022): the derivative of ratio
//   tracking's product of (1 - sigma_t d(x_i) / rate_i) over its own tentative
//   collisions x_i, with the rate floored above 0 so that voxels in empty majorant cells
//   are reached (without the floor their gradient is lost).
// Each with several budgets (4 to 32 points; rate floors 0.1 to 4), and each must be
// unbiased against quadrature. The test prints each one's squared error per ray summed
// over the voxels, its points and time per ray on this core and its efficiency against
// the renderer's, which docs/gradients.md quotes; timings are not checked.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/format_text.h"
#include "host_density_grid.h"
#include "volume/smoke_plume.h"

namespace vkdr::test {
namespace {

constexpr int kResolution = 32;
constexpr float kSigmaT = 10.0f;    // the experiment's plume: sigma_s 10, sigma_a 0.25 per unit density
constexpr uint kRays = 12;
constexpr uint kRepetitions = 3000;

// The plume in the unit cube [0, 1]^3 (index = kResolution world).
HostDensityGrid plumeGrid() {
    return HostDensityGrid(ivec3(0), ivec3(kResolution), makeSmokePlume(kResolution, 1).values, float(kResolution),
                           1.0f);
}

struct Ray {
    vec3 origin;
    vec3 direction;
    float length;
};

// Rays from one side of the cube to the other through its middle third, where the plume is.
std::vector<Ray> raysThroughThePlume() {
    std::mt19937 random(5);
    std::uniform_real_distribution<float> middle(0.33f, 0.67f);
    std::vector<Ray> rays;
    for (uint i = 0; i < kRays; ++i) {
        const int axis = int(i % 3);
        vec3 from(middle(random), middle(random), middle(random)), to(middle(random), middle(random), middle(random));
        from[axis] = -0.05f;
        to[axis] = 1.05f;
        rays.push_back({from, normalize(to - from), length(to - from)});
    }
    return rays;
}

// One estimate of every voxel's gradient, added as the device adds them (one add per
// point and voxel), into a dense array with a list of the voxels touched.
struct GradientEstimate {
    std::vector<double> values;
    std::vector<int> touched;
    int points = 0;

    explicit GradientEstimate(size_t voxels) : values(voxels, 0.0) {}

    void addTrilinear(const HostDensityGrid& grid, vec3 index, double g) {
        ++points;
        const vec3 base = floor(index);
        for (int corner = 0; corner < 8; ++corner) {
            const ivec3 offset = trilinearCorner(corner);
            const int voxel = grid.offset(ivec3(base) + offset);
            if (voxel < 0) continue;
            if (values[size_t(voxel)] == 0.0) touched.push_back(voxel);
            values[size_t(voxel)] += g * double(trilinearWeight(index - base, offset));
        }
    }
};

// The exact gradient: -sigma_t T integral of w_v, by the midpoint rule.
std::vector<double> exactGradient(const HostDensityGrid& grid, const Ray& ray) {
    constexpr int kSteps = 40000;
    GradientEstimate integral(grid.voxels.size());
    double depth = 0.0;
    const double step = double(ray.length) / kSteps;
    for (int i = 0; i < kSteps; ++i) {
        const vec3 p = ray.origin + float((i + 0.5) * step) * ray.direction;
        depth += step * grid.density(dvec3(p));
        integral.addTrilinear(grid, p * grid.voxelsPerUnit, step);
    }
    const double transmittance = std::exp(-double(kSigmaT) * depth);
    for (double& value : integral.values) value *= -double(kSigmaT) * transmittance;
    return integral.values;
}

// The renderer's estimator with `pointCount` points (kDensityIntegralPoints on the device).
void stratifiedEstimate(const HostDensityGrid& grid, const Ray& ray, uint pointCount, uint repetition,
                        GradientEstimate& estimate) {
    TrackingRandom random = trackingRandom(repetition, 0u, 0u, 0u, kTrackingShadow, 1u);
    TrackingRandom points = trackingRandom(repetition, 0u, 0u, 0u, kTrackingShadowGradient, 1u);
    uint stepsLeft = kMaxTransmittanceSteps;
    bool truncated = false;
    const float transmittance =
        ratioTrackTransmittance(grid.grid, ray.origin, ray.direction, ray.length, vec3(kSigmaT), random, stepsLeft,
                                truncated)
            .x;
    const GridRay indexRay = gridRay(grid.grid, ray.origin, ray.direction);
    const vec2 interval = cellsInterval(grid.grid, indexRay, ray.length);
    if (!(interval.x < interval.y) || transmittance == 0.0f) return;
    const float u = nextTrackingRandom(points).x;
    const float length = (interval.y - interval.x) / float(pointCount);
    for (uint k = 0; k < pointCount; ++k) {
        const float t = interval.x + (float(k) + u) * length;
        estimate.addTrilinear(grid, indexRay.origin + t * indexRay.direction, -double(kSigmaT) * transmittance * length);
    }
}

struct TentativeCollision {
    vec3 index;
    float rate;
    float ratio;
};

// With tentative collisions at the rate sigma_t max(majorant, rateFloor).
void differentialRatioTracking(const HostDensityGrid& grid, const Ray& ray, float rateFloor, uint repetition,
                               GradientEstimate& estimate, std::vector<TentativeCollision>& collisions) {
    TrackingRandom random = trackingRandom(repetition, 0u, 0u, 0u, kTrackingShadow, 2u);
    const GridRay indexRay = gridRay(grid.grid, ray.origin, ray.direction);
    MajorantWalk walk = startMajorantWalk(grid.grid, indexRay, ray.length);
    collisions.clear();
    float tau = -std::log(1.0f - nextTrackingRandom(random).x);
    while (!walkDone(walk)) {
        const float exit = cellExit(walk);
        const float rate = kSigmaT * std::max(gridMajorant(grid.grid, walk.cell), rateFloor);
        if (tau < rate * (exit - walk.t)) {
            walk.t += tau / rate;
            const vec3 index = indexRay.origin + walk.t * indexRay.direction;
            collisions.push_back({index, rate, 1.0f - kSigmaT * gridDensity(grid.grid, index) / rate});
            tau = -std::log(1.0f - nextTrackingRandom(random).x);
            continue;
        }
        tau -= rate * (exit - walk.t);
        advanceToNextCell(walk, grid.grid);
    }
    // d/d(voxel) of the product: at each collision, its own ratio's derivative times the
    // product of the others (before it and after it, without dividing by a ratio of 0).
    std::vector<double> after(collisions.size() + 1, 1.0);
    for (size_t i = collisions.size(); i-- > 0;) after[i] = after[i + 1] * double(collisions[i].ratio);
    double before = 1.0;
    for (size_t i = 0; i < collisions.size(); ++i) {
        estimate.addTrilinear(grid, collisions[i].index, -double(kSigmaT) / collisions[i].rate * before * after[i + 1]);
        before *= double(collisions[i].ratio);
    }
}

using Estimator = std::function<void(const Ray&, uint repetition, GradientEstimate&)>;

struct Comparison {
    std::string name;
    Estimator estimator;
    double squaredError = 0.0;  // per ray, summed over the voxels
    double seconds = 0.0;       // per ray
    double points = 0.0;        // per ray: gradient points (each adds to 8 voxels)
    double worstZ = 0.0;        // of the per-ray gradient's projections against the exact one
    double sum[3] = {}, sumOfSquares[3] = {};
};

// Runs every estimator kRepetitions times per ray, in turn so that the machine's load
// falls on all alike: its mean squared error, time and points, and whether its mean is
// unbiased along three projections of the gradient (every voxel alike, and two random
// signs per voxel), each against its standard error.
void compare(const HostDensityGrid& grid, const std::vector<Ray>& rays, std::vector<Comparison>& comparisons) {
    std::mt19937 random(9);
    std::vector<double> signs[2];
    for (std::vector<double>& s : signs) {
        for (size_t v = 0; v < grid.voxels.size(); ++v) s.push_back(random() % 2 ? 1.0 : -1.0);
    }
    GradientEstimate estimate(grid.voxels.size());
    for (const Ray& ray : rays) {
        const std::vector<double> exact = exactGradient(grid, ray);
        double exactProjection[3] = {0.0, 0.0, 0.0}, exactSquares = 0.0;
        for (size_t v = 0; v < exact.size(); ++v) {
            exactProjection[0] += exact[v];
            exactProjection[1] += signs[0][v] * exact[v];
            exactProjection[2] += signs[1][v] * exact[v];
            exactSquares += exact[v] * exact[v];
        }
        for (Comparison& c : comparisons) std::fill_n(c.sum, 3, 0.0), std::fill_n(c.sumOfSquares, 3, 0.0);
        for (uint r = 0; r < kRepetitions; ++r) {
            for (Comparison& c : comparisons) {
                const auto start = std::chrono::steady_clock::now();
                c.estimator(ray, r, estimate);
                c.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                c.points += double(estimate.points);
                // sum over voxels of (estimate - exact)^2, the untouched ones adding exact^2
                double squaredError = exactSquares;
                double projection[3] = {0.0, 0.0, 0.0};
                for (int v : estimate.touched) {
                    const double g = estimate.values[size_t(v)];
                    squaredError += g * g - 2.0 * g * exact[size_t(v)];
                    projection[0] += g;
                    projection[1] += signs[0][size_t(v)] * g;
                    projection[2] += signs[1][size_t(v)] * g;
                    estimate.values[size_t(v)] = 0.0;
                }
                estimate.touched.clear();
                estimate.points = 0;
                c.squaredError += squaredError;
                for (int k = 0; k < 3; ++k) {
                    c.sum[k] += projection[k];
                    c.sumOfSquares[k] += projection[k] * projection[k];
                }
            }
        }
        for (Comparison& c : comparisons) {
            for (int k = 0; k < 3; ++k) {
                const double mean = c.sum[k] / kRepetitions;
                const double standardError =
                    std::sqrt(std::max(0.0, c.sumOfSquares[k] / kRepetitions - mean * mean) / (kRepetitions - 1));
                const double z = std::abs(mean - exactProjection[k]) / standardError;
                c.worstZ = std::max(c.worstZ, std::isfinite(z) ? z : 1e30);
            }
        }
    }
    const double estimates = double(rays.size()) * kRepetitions;
    for (Comparison& c : comparisons) {
        c.squaredError /= estimates;
        c.seconds /= estimates;
        c.points /= estimates;
    }
}

TEST(TransmittanceGradient, BothEstimatorsAreUnbiasedAndTheirEfficiencyIsReported) {
    const HostDensityGrid grid = plumeGrid();
    grid.bind();
    std::vector<TentativeCollision> collisions;
    std::vector<Comparison> comparisons;
    for (uint points : {kDensityIntegralPoints, 8u, 16u, 32u}) {
        comparisons.push_back({formatText("%u stratified points%s", points,
                                          points == kDensityIntegralPoints ? " (the renderer's)" : ""),
                               [&grid, points](const Ray& ray, uint r, GradientEstimate& e) {
                                   stratifiedEstimate(grid, ray, points, r, e);
                               }});
    }
    for (float floor : {0.1f, 0.3f, 1.0f, 2.0f, 4.0f}) {
        comparisons.push_back({formatText("differential ratio tracking, rate floor %g", floor),
                               [&grid, &collisions, floor](const Ray& ray, uint r, GradientEstimate& e) {
                                   differentialRatioTracking(grid, ray, floor, r, e, collisions);
                               }});
    }
    compare(grid, raysThroughThePlume(), comparisons);
    const Comparison& renderers = comparisons[0];
    for (const Comparison& c : comparisons) {
        EXPECT_LT(c.worstZ, 5.0) << c.name;
        std::printf("%-45s squared error %7.4f, %5.1f points, %5.2f us per ray, efficiency / the renderer's %.2f\n",
                    c.name.c_str(), c.squaredError, c.points, c.seconds * 1e6,
                    (renderers.squaredError * renderers.seconds) / (c.squaredError * c.seconds));
    }
}

}  // namespace
}  // namespace vkdr::test
