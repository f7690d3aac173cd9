// The held-out view's error against hand-computed images: a perfect render, a uniformly
// biased one, and one whose excess over the true render's error is pure noise.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "optimize/held_out_error.h"

namespace vkdr::test {
namespace {

Image constantImage(int width, int height, float value) {
    return Image{width, height, std::vector<float>(size_t(width * height * 3), value)};
}

TEST(HeldOutError, IsTheFloorForTheTrueRenderAndGrowsWithABias) {
    Image target = constantImage(8, 8, 2.0f);
    Image trueRender = target;
    for (size_t i = 0; i < trueRender.rgb.size(); ++i) trueRender.rgb[i] += (i % 2 ? 0.2f : -0.2f);
    HeldOutError same = heldOutError(trueRender, trueRender, target);
    EXPECT_NEAR(same.relativeRmse, 0.1, 1e-6);  // 0.2 off everywhere, over a mean of 2
    EXPECT_EQ(same.relativeRmse, same.floorRelativeRmse);
    EXPECT_EQ(same.excessInStandardErrors, 0.0);

    // A render 0.4 too bright where the true one is 0.2 off: relative RMSE sqrt(mean of
    // 0.6^2 and 0.2^2) / 2, and every pixel's excess error is positive.
    Image biased = trueRender;
    for (float& value : biased.rgb) value += 0.4f;
    HeldOutError error = heldOutError(biased, trueRender, target);
    EXPECT_NEAR(error.relativeRmse, std::sqrt((0.36 + 0.04) / 2.0) / 2.0, 1e-6);
    EXPECT_GT(error.excessInStandardErrors, 10.0);
}

// Independent noise of the same spread in both renders: the excess, in its own standard
// errors, is a standard normal draw; over many draws its mean is 0 and its spread 1.
TEST(HeldOutError, ExcessOfEqualNoiseIsAStandardNormalDraw) {
    std::mt19937 random(3);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    Image target = constantImage(32, 32, 1.0f);
    const int draws = 400;
    double sum = 0.0, sumOfSquares = 0.0;
    for (int draw = 0; draw < draws; ++draw) {
        Image render = target, trueRender = target;
        for (size_t i = 0; i < target.rgb.size(); ++i) {
            render.rgb[i] += noise(random);
            trueRender.rgb[i] += noise(random);
        }
        const double excess = heldOutError(render, trueRender, target).excessInStandardErrors;
        sum += excess;
        sumOfSquares += excess * excess;
    }
    const double mean = sum / draws, variance = sumOfSquares / draws - mean * mean;
    // The mean of 400 standard normal draws has standard error 0.05; their variance
    // about 0.07 (sqrt(2 / 400)).
    EXPECT_NEAR(mean, 0.0, 5 * 0.05);
    EXPECT_NEAR(variance, 1.0, 5 * 0.071);
}

TEST(HeldOutError, RefusesImagesOfAnotherSizeAndABlackTarget) {
    Image target = constantImage(4, 4, 1.0f);
    EXPECT_THROW(heldOutError(constantImage(4, 3, 1.0f), target, target), Error);
    EXPECT_THROW(heldOutError(target, target, constantImage(4, 4, 0.0f)), Error);
}

}  // namespace
}  // namespace vkdr::test
