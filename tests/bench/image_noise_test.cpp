// The benchmark's noise figure: the per-pixel relative noise from two renders that differ
// only in the seed.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "bench/image_noise.h"

namespace vkdr::test {
namespace {

// Two images whose every pixel is `mean` times (1 + relative noise), independently.
std::pair<Image, Image> noisyPair(int side, double relative, double mean) {
    std::mt19937_64 random(7);
    std::normal_distribution<double> normal(0.0, relative);
    Image a{side, side, std::vector<float>(size_t(side) * side * 3)};
    Image b = a;
    for (size_t p = 0; p < a.rgb.size(); p += 3) {
        const float va = float(mean * (1.0 + normal(random))), vb = float(mean * (1.0 + normal(random)));
        for (int c = 0; c < 3; ++c) {
            a.rgb[p + c] = va;
            b.rgb[p + c] = vb;
        }
    }
    return {a, b};
}

TEST(ImageNoise, RecoversTheRelativeNoiseOfEachRender) {
    // 40000 pixels estimate the noise to sqrt(1 / (2 x 40000)) = 0.35 % (one standard
    // error); dividing by the pair's own mean raises it by about 3/4 of noise^2 = 0.75 %
    // at 10 %. Within 2 %: that bias plus 3.5 standard errors.
    auto [a, b] = noisyPair(200, 0.1, 0.4);
    std::optional<double> noise = relativeNoise(a, b);
    ASSERT_TRUE(noise.has_value());
    EXPECT_NEAR(*noise, 0.1, 0.002);
}

TEST(ImageNoise, BlackPixelsAreLeftOutAndABlackImageHasNone) {
    auto [a, b] = noisyPair(200, 0.1, 0.4);
    Image blackA{200, 200, std::vector<float>(200 * 200 * 3, 0.0f)};
    Image blackB = blackA;
    EXPECT_FALSE(relativeNoise(blackA, blackB).has_value());
    // Half of each image black: the same noise from the lit half.
    for (size_t p = 0; p < a.rgb.size() / 2; ++p) {
        a.rgb[p] = b.rgb[p] = 0.0f;
    }
    EXPECT_NEAR(*relativeNoise(a, b), 0.1, 0.003);
    EXPECT_FALSE(relativeNoise(a, Image{100, 100, std::vector<float>(100 * 100 * 3, 1.0f)}).has_value());
}

}  // namespace
}  // namespace vkdr::test
