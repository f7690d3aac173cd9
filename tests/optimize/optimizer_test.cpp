// Adam and SGD on their own: known steps and convergence on a quadratic.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "optimize/adam.h"
#include "optimize/optimizer.h"
#include "optimize/sgd.h"

namespace vkdr::test {
namespace {

// Minimises sum_i scale_i (x_i - target_i)^2 from x = 0.
std::vector<double> minimise(Optimizer& optimizer, const std::vector<double>& target, const std::vector<double>& scale,
                             int steps) {
    std::vector<double> x(target.size(), 0.0);
    for (int step = 0; step < steps; ++step) {
        std::vector<double> gradient;
        for (size_t i = 0; i < x.size(); ++i) gradient.push_back(2.0 * scale[i] * (x[i] - target[i]));
        optimizer.step(x, gradient);
    }
    return x;
}

TEST(Adam, FirstStepMovesEachValueByItsLearningRateWhateverTheGradientScale) {
    // With bias correction, m_hat = g and v_hat = g^2 after one step: the step is lr * sign(g).
    AdamOptimizer adam({0.1, 0.01});
    std::vector<double> x = {1.0, 1.0};
    adam.step(x, std::vector<double>{1e-2, -1e6});
    EXPECT_NEAR(x[0], 0.9, 1e-6);
    EXPECT_NEAR(x[1], 1.01, 1e-9);
}

// Epsilon is in the gradient's units: a gradient of 1e-10 moves a value by a hundredth
// of its rate with the default 1e-8, and by the rate with an epsilon far below it.
TEST(Adam, EpsilonDecidesWhetherATinyGradientTakesAFullStep) {
    std::vector<double> x = {1.0};
    AdamOptimizer standard({0.1});
    standard.step(x, std::vector<double>{1e-10});
    EXPECT_NEAR(x[0], 1.0 - 0.1 * 1e-10 / (1e-10 + 1e-8), 1e-12);
    x = {1.0};
    std::unique_ptr<Optimizer> small = makeOptimizer(OptimizerKind::Adam, {0.1}, 1e-20);
    small->step(x, std::vector<double>{1e-10});
    EXPECT_NEAR(x[0], 0.9, 1e-9);
}

TEST(Adam, MinimisesAQuadraticWhoseCurvaturesDifferByOrdersOfMagnitude) {
    AdamOptimizer adam(std::vector<double>(3, 0.02));
    std::vector<double> x = minimise(adam, {0.5, -0.25, 0.05}, {1e-4, 1.0, 1e4}, 2000);
    EXPECT_NEAR(x[0], 0.5, 1e-3);
    EXPECT_NEAR(x[1], -0.25, 1e-3);
    EXPECT_NEAR(x[2], 0.05, 1e-3);
}

TEST(Sgd, StepsAgainstTheGradientScaledByTheLearningRate) {
    SgdOptimizer sgd({0.5});
    std::vector<double> x = {1.0};
    sgd.step(x, std::vector<double>{0.25});
    EXPECT_DOUBLE_EQ(x[0], 0.875);
}

TEST(Sgd, MinimisesAQuadratic) {
    SgdOptimizer sgd(std::vector<double>(2, 0.1));
    std::vector<double> x = minimise(sgd, {0.3, -0.7}, {1.0, 2.0}, 200);
    EXPECT_NEAR(x[0], 0.3, 1e-9);
    EXPECT_NEAR(x[1], -0.7, 1e-9);
}

TEST(Optimizer, ParsesNamesAndRejectsOthers) {
    EXPECT_EQ(parseOptimizerKind("adam"), OptimizerKind::Adam);
    EXPECT_EQ(parseOptimizerKind("sgd"), OptimizerKind::Sgd);
    EXPECT_EQ(optimizerKindName(OptimizerKind::Sgd), "sgd");
    EXPECT_THROW(parseOptimizerKind("lbfgs"), Error);
}

TEST(Optimizer, RejectsALearningRateThatIsNotPositive) {
    EXPECT_THROW(makeOptimizer(OptimizerKind::Adam, {0.1, 0.0}, 1e-8), Error);
    EXPECT_THROW(makeOptimizer(OptimizerKind::Sgd, {-1.0}, 1e-8), Error);
    EXPECT_THROW(makeOptimizer(OptimizerKind::Sgd, {NAN}, 1e-8), Error);
    EXPECT_THROW(makeOptimizer(OptimizerKind::Adam, {0.1}, 0.0), Error);
}

}  // namespace
}  // namespace vkdr::test
