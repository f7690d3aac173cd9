#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "image/srgb.h"

namespace vkdr {
namespace {

TEST(Srgb, KnownValues) {
    EXPECT_EQ(srgbFromLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbFromLinear(1.0f), 1.0f);
    EXPECT_NEAR(srgbFromLinear(0.5f), 0.735357f, 1e-6f);
    EXPECT_NEAR(srgbFromLinear(0.18f), 0.461356f, 1e-6f);
    EXPECT_FLOAT_EQ(srgbFromLinear(0.001f), 0.01292f);  // linear segment
    EXPECT_NEAR(linearFromSrgb(0.5f), 0.214041f, 1e-6f);
    EXPECT_FLOAT_EQ(linearFromSrgb(0.04f), 0.04f / 12.92f);
}

TEST(Srgb, PiecesMeetAtTheThreshold) {
    float below = srgbFromLinear(std::nextafter(0.0031308f, 0.0f));
    float above = srgbFromLinear(std::nextafter(0.0031308f, 1.0f));
    EXPECT_NEAR(below, 0.04045f, 1e-5f);
    EXPECT_NEAR(above, 0.04045f, 1e-5f);
}

TEST(Srgb, EncodeClampsToTheUnitInterval) {
    EXPECT_EQ(srgbFromLinear(-1.0f), 0.0f);
    EXPECT_EQ(srgbFromLinear(2.0f), srgbFromLinear(1.0f));
    EXPECT_EQ(srgbFromLinear(std::numeric_limits<float>::infinity()), srgbFromLinear(1.0f));
    EXPECT_EQ(srgbFromLinear(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Srgb, DecodeInvertsEncode) {
    for (int i = 0; i <= 1000; ++i) {
        float linear = i / 1000.0f;
        EXPECT_NEAR(linearFromSrgb(srgbFromLinear(linear)), linear, 2e-6f) << linear;
    }
}

}  // namespace
}  // namespace vkdr
