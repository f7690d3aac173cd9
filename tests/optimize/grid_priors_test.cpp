// The priors on density grids: the smoothness, sparsity and total variation terms' values
// on grids whose sums are known by hand, the smoothness and total variation gradients
// against central differences of their values, GridPriorLossGradient adding them to the
// inner LossGradient's, and the weights refused without a grid to put them on.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/error.h"
#include "optimize/grid_priors.h"

namespace vkdr::test {
namespace {

DensityGrid gridOf(glm::ivec3 size, std::vector<float> values) {
    DensityGrid grid;
    grid.size = size;
    grid.values = std::move(values);
    return grid;
}

TEST(GridSmoothness, ValueSumsSquaredDifferencesOfFaceNeighbours) {
    EXPECT_EQ(gridSmoothness(gridOf({2, 2, 2}, std::vector<float>(8, 0.7f)), 3.0, nullptr), 0.0);
    // Two voxels: one pair, over two voxels.
    EXPECT_DOUBLE_EQ(gridSmoothness(gridOf({2, 1, 1}, {1.0f, 4.0f}), 2.0, nullptr), 2.0 / 2.0 * 9.0);
    // A 2x2x1 grid: four pairs (two along x, two along y), over four voxels.
    EXPECT_DOUBLE_EQ(gridSmoothness(gridOf({2, 2, 1}, {0.0f, 1.0f, 2.0f, 3.0f}), 1.0, nullptr),
                     (1.0 + 1.0 + 4.0 + 4.0) / 4.0);
}

// Random values in [0, 2) on a grid of `size`.
DensityGrid randomGrid(glm::ivec3 size, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> value(0.0f, 2.0f);
    DensityGrid grid = gridOf(size, {});
    for (size_t i = 0; i < grid.voxelCount(); ++i) {
        grid.values.push_back(value(random));
    }
    return grid;
}

// `term`'s gradient on `grid` against central differences of its value with step h in
// each voxel; returns the gradient.
template <typename Term>
std::vector<double> expectGradientMatchesCentralDifferences(Term term, const DensityGrid& grid, double weight, float h,
                                                            double tolerance) {
    std::vector<double> gradient(grid.voxelCount(), 0.0);
    term(grid, weight, &gradient);
    for (size_t i = 0; i < grid.voxelCount(); ++i) {
        DensityGrid up = grid, down = grid;
        up.values[i] += h;
        down.values[i] -= h;
        const double difference = (term(up, weight, nullptr) - term(down, weight, nullptr)) / (2.0 * double(h));
        EXPECT_NEAR(gradient[i], difference, tolerance) << "voxel " << i;
    }
    return gradient;
}

// The term is quadratic: a central difference is exact up to rounding.
TEST(GridSmoothness, GradientMatchesCentralDifferences) {
    expectGradientMatchesCentralDifferences(gridSmoothness, randomGrid({3, 4, 2}, 5), 0.8, 1.0f / 64.0f, 1e-6);
}

TEST(GridTotalVariation, ValueSumsAbsoluteDifferencesOfFaceNeighbours) {
    EXPECT_EQ(gridTotalVariation(gridOf({2, 2, 2}, std::vector<float>(8, 0.7f)), 3.0, nullptr), 0.0);
    EXPECT_DOUBLE_EQ(gridTotalVariation(gridOf({2, 1, 1}, {4.0f, 1.0f}), 2.0, nullptr), 2.0 / 2.0 * 3.0);
    // A 2x2x1 grid: pairs (0,1) and (2,3) along x differ by 1, (0,2) and (1,3) along y by 2.
    EXPECT_DOUBLE_EQ(gridTotalVariation(gridOf({2, 2, 1}, {0.0f, 1.0f, 2.0f, 3.0f}), 1.0, nullptr),
                     (1.0 + 1.0 + 2.0 + 2.0) / 4.0);
}

// Random values have no equal neighbours, and a step smaller than every difference keeps
// each term on one side of its kink, where |d| is linear: the central difference is exact
// but for the rounding of the stepped values to float (about 6e-8 / (2 h) per pair, times
// the weight over the voxels).
TEST(GridTotalVariation, GradientMatchesCentralDifferences) {
    const std::vector<double> gradient = expectGradientMatchesCentralDifferences(
        gridTotalVariation, randomGrid({3, 2, 4}, 7), 1.5, 1.0f / 4096.0f, 1e-4);
    EXPECT_GT(*std::max_element(gradient.begin(), gradient.end()), 0.0);
}

// A LossGradient returning zero loss and gradients, to see what the smoothing adds.
class ZeroLossGradient : public LossGradient {
public:
    GradientResult evaluate(const Scene& scene, uint32_t) override {
        GradientResult result;
        result.parameters.push_back({"media/smoke/density", scene.densityGrids[0].grid.values,
                                     std::vector<double>(scene.densityGrids[0].grid.voxelCount(), 0.0)});
        return result;
    }
};

TEST(GridSparsity, IsTheWeightedMeanDensityWithAConstantGradient) {
    std::vector<double> gradient(4, 1.0);
    EXPECT_DOUBLE_EQ(gridSparsity(gridOf({2, 2, 1}, {0.0f, 1.0f, 2.0f, 5.0f}), 3.0, &gradient), 3.0 * 8.0 / 4.0);
    for (double value : gradient) EXPECT_DOUBLE_EQ(value, 1.0 + 3.0 / 4.0);
}

TEST(GridPriors, GridPriorLossGradientAddsTheTermsAndTheirGradients) {
    Scene scene;
    scene.media.push_back({.name = "smoke", .sigma_s = glm::vec3(1.0f), .densityGrid = 0});
    scene.densityGrids.push_back({"", gridOf({2, 1, 1}, {1.0f, 4.0f}), glm::dmat4(1.0)});
    ZeroLossGradient inner;
    GridPriorLossGradient smoothed(inner, {{"media/smoke/density", {.smoothness = 2.0}}});
    GradientResult result = smoothed.evaluate(scene, 0);
    EXPECT_DOUBLE_EQ(result.loss, 9.0);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[0], -6.0);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[1], 6.0);

    // Sparsity 0.5: the loss gains 0.5 * (1 + 4) / 2, each voxel's gradient 0.5 / 2.
    GridPriorLossGradient both(inner, {{"media/smoke/density", {.smoothness = 2.0, .sparsity = 0.5}}});
    result = both.evaluate(scene, 0);
    EXPECT_DOUBLE_EQ(result.loss, 9.0 + 1.25);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[0], -6.0 + 0.25);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[1], 6.0 + 0.25);

    // Total variation 3: the loss gains 3 * |1 - 4| / 2, the voxels' gradients -/+ 3 / 2.
    GridPriorLossGradient edges(inner, {{"media/smoke/density", {.totalVariation = 3.0}}});
    result = edges.evaluate(scene, 0);
    EXPECT_DOUBLE_EQ(result.loss, 4.5);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[0], -1.5);
    EXPECT_DOUBLE_EQ(result.parameters[0].gradient[1], 1.5);

    GridPriorLossGradient wrong(inner, {{"media/smoke/sigma_s", {.smoothness = 2.0}}});
    EXPECT_THROW(wrong.evaluate(scene, 0), Error);
}

TEST(GridPriors, WeightsGoToEveryGridAndNeedOne) {
    const std::vector<std::string> names = {"media/fog/sigma_s", "media/smoke/density", "media/plume/density"};
    std::map<std::string, GridPriorWeights> weights = gridPriorWeights(names, {.sparsity = 0.5});
    ASSERT_EQ(weights.size(), 2u);
    EXPECT_EQ(weights["media/plume/density"].sparsity, 0.5);
    EXPECT_TRUE(gridPriorWeights({"media/fog/sigma_s"}, {}).empty());
    EXPECT_THROW(gridPriorWeights({"media/fog/sigma_s"}, {.sparsity = 0.5}), Error);
    EXPECT_THROW(gridPriorWeights({"media/fog/sigma_s"}, {.smoothness = 0.5}), Error);
    EXPECT_THROW(gridPriorWeights({"media/fog/sigma_s"}, {.totalVariation = 0.5}), Error);
    EXPECT_EQ(gridPriorWeights(names, {.totalVariation = 0.25})["media/smoke/density"].totalVariation, 0.25);
}

}  // namespace
}  // namespace vkdr::test
