#include <gtest/gtest.h>

#include "bench/median.h"

namespace vkdr::test {
namespace {

TEST(Median, OddCountTakesTheMiddleValue) {
    EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
    EXPECT_EQ(median({7.0}), 7.0);
}

TEST(Median, EvenCountAveragesTheTwoMiddleValues) {
    EXPECT_EQ(median({4.0, 1.0, 3.0, 100.0}), 3.5);
    EXPECT_EQ(median({2.0, 2.0}), 2.0);
}

TEST(Median, NoValuesGiveZero) {
    EXPECT_EQ(median({}), 0.0);
}

}  // namespace
}  // namespace vkdr::test
