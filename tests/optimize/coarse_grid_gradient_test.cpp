// Coarse-to-fine levels for density grids: the interpolation from the coarse grid (a
// partition of unity that reproduces linear ramps), its transpose (by the adjoint
// identity), the schedule of levels, and the claim that plain gradient descent with the
// coarsened gradient is gradient descent on the coarse grid's values.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "optimize/coarse_grid_gradient.h"

namespace vkdr::test {
namespace {

size_t voxels(glm::ivec3 size) { return size_t(size.x) * size_t(size.y) * size_t(size.z); }

std::vector<double> randomValues(size_t count, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<double> values(count);
    for (double& v : values) v = value(random);
    return values;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
    return sum;
}

TEST(CoarseGridGradient, CoarseGridsCoverTheGridRoundingUp) {
    EXPECT_EQ(coarseGridSize({64, 64, 64}, 4), glm::ivec3(16, 16, 16));
    EXPECT_EQ(coarseGridSize({7, 5, 3}, 2), glm::ivec3(4, 3, 2));
    EXPECT_EQ(coarseGridSize({7, 5, 3}, 8), glm::ivec3(1, 1, 1));
}

TEST(CoarseGridGradient, InterpolationIsAPartitionOfUnityAndReproducesRamps) {
    const glm::ivec3 size{12, 7, 5};
    for (uint32_t divisor : {2u, 4u}) {
        SCOPED_TRACE(divisor);
        const glm::ivec3 coarse = coarseGridSize(size, divisor);
        std::vector<double> fine(voxels(size));
        prolongGrid(size, divisor, std::vector<double>(voxels(coarse), 0.7), fine);
        for (double value : fine) EXPECT_NEAR(value, 0.7, 1e-12);

        // Coarse voxel c sits at fine coordinate (c + 0.5) D - 0.5: a ramp through those
        // positions gives each fine voxel between the first and last coarse voxel its index.
        std::vector<double> ramp;
        for (int z = 0; z < coarse.z; ++z)
            for (int y = 0; y < coarse.y; ++y)
                for (int x = 0; x < coarse.x; ++x) ramp.push_back((x + 0.5) * divisor - 0.5);
        prolongGrid(size, divisor, ramp, fine);
        const double first = 0.5 * divisor - 0.5, last = (coarse.x - 0.5) * divisor - 0.5;
        for (int x = 0; x < size.x; ++x) {
            const double expected = std::clamp(double(x), first, last);
            EXPECT_NEAR(fine[size_t(x)], expected, 1e-12) << "x " << x;
            EXPECT_NEAR(fine[voxels(size) - size_t(size.x) + size_t(x)], expected, 1e-12) << "x " << x;
        }
    }
}

TEST(CoarseGridGradient, TransposeSatisfiesTheAdjointIdentity) {
    const glm::ivec3 size{9, 6, 5};
    for (uint32_t divisor : {1u, 2u, 4u}) {
        SCOPED_TRACE(divisor);
        const std::vector<double> coarse = randomValues(voxels(coarseGridSize(size, divisor)), 1);
        const std::vector<double> fine = randomValues(voxels(size), 2);
        std::vector<double> prolonged(voxels(size)), transposed(coarse.size());
        prolongGrid(size, divisor, coarse, prolonged);
        prolongGridTransposed(size, divisor, fine, transposed);
        EXPECT_NEAR(dot(prolonged, fine), dot(coarse, transposed), 1e-12 * double(fine.size()));
    }
}

TEST(CoarseGridGradient, LevelsSplitTheRunEquallyFromCoarsestToTheGridsOwn) {
    for (uint32_t i : {0u, 29u}) EXPECT_EQ(gridDivisorAt(i, 90, 3), 4u);
    for (uint32_t i : {30u, 59u}) EXPECT_EQ(gridDivisorAt(i, 90, 3), 2u);
    for (uint32_t i : {60u, 89u}) EXPECT_EQ(gridDivisorAt(i, 90, 3), 1u);
    EXPECT_EQ(gridDivisorAt(0, 90, 1), 1u);
    EXPECT_EQ(gridDivisorAt(0, 2, 4), 8u);  // fewer iterations than levels: the first level still starts it
    EXPECT_EQ(gridDivisorAt(1, 2, 4), 2u);
}

// Gradient descent on the fine grid with U U^T g, from a grid U c0, stays U c_k where
// c_k is gradient descent on the coarse values with their gradient U^T g.
TEST(CoarseGridGradient, DescentWithTheCoarsenedGradientIsDescentOnTheCoarseGrid) {
    const glm::ivec3 size{8, 6, 4};
    const uint32_t divisor = 2;
    const std::vector<double> target = randomValues(voxels(size), 3);
    std::vector<double> coarse = randomValues(voxels(coarseGridSize(size, divisor)), 4);
    std::vector<double> fine(voxels(size));
    prolongGrid(size, divisor, coarse, fine);
    const double rate = 0.05;
    auto gradientAt = [&](const std::vector<double>& values) {
        std::vector<double> gradient(values.size());
        for (size_t i = 0; i < values.size(); ++i) gradient[i] = 2.0 * (values[i] - target[i]);
        return gradient;
    };
    for (int step = 0; step < 5; ++step) {
        std::vector<double> fineGradient = gradientAt(fine);
        coarsenGridGradient(size, divisor, fineGradient);
        for (size_t i = 0; i < fine.size(); ++i) fine[i] -= rate * fineGradient[i];

        std::vector<double> prolonged(fine.size()), coarseGradient(coarse.size());
        prolongGrid(size, divisor, coarse, prolonged);
        prolongGridTransposed(size, divisor, gradientAt(prolonged), coarseGradient);
        for (size_t i = 0; i < coarse.size(); ++i) coarse[i] -= rate * coarseGradient[i];
    }
    std::vector<double> expected(fine.size());
    prolongGrid(size, divisor, coarse, expected);
    for (size_t i = 0; i < fine.size(); ++i) EXPECT_NEAR(fine[i], expected[i], 1e-9) << i;
}

}  // namespace
}  // namespace vkdr::test
