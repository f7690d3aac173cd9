// The parts of report.html that carry numbers: the percentile that scales the
// difference images, the colour map and its bar, base64, the parameter table and the
// trajectory and metric charts, and the summaries of parameters of many values.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "optimize/base64.h"
#include "optimize/difference_colour_map.h"
#include "optimize/loss_chart.h"
#include "optimize/parameter_table.h"
#include "optimize/metric_chart.h"
#include "optimize/trajectory_chart.h"
#include "optimize/value_summary.h"

namespace vkdr::test {
namespace {

using Colour = std::array<uint8_t, 3>;

size_t occurrences(const std::string& text, const std::string& part) {
    size_t count = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

TEST(NearestRankPercentile, IsTheSmallestValueWithThatFractionAtOrBelowIt) {
    std::vector<float> values(100);
    std::iota(values.begin(), values.end(), 1.0f);  // 1, 2, ..., 100
    std::shuffle(values.begin(), values.end(), std::mt19937(5));
    EXPECT_EQ(nearestRankPercentile(values, 0.99), 99.0f);
    EXPECT_EQ(nearestRankPercentile(values, 0.5), 50.0f);
    EXPECT_EQ(nearestRankPercentile(values, 0.505), 51.0f);  // 50.5 values must be at or below: rank 51
    EXPECT_EQ(nearestRankPercentile(values, 1.0), 100.0f);
    EXPECT_EQ(nearestRankPercentile(values, 0.001), 1.0f);
    EXPECT_EQ(nearestRankPercentile({}, 0.99), 0.0f);
}

TEST(DifferenceColour, RunsThroughItsStopsAndClampsOutsideThem) {
    EXPECT_EQ(differenceColour(0.0f), (Colour{0, 0, 4}));
    EXPECT_EQ(differenceColour(0.5f), (Colour{188, 55, 84}));
    EXPECT_EQ(differenceColour(1.0f), (Colour{252, 255, 164}));
    EXPECT_EQ(differenceColour(7.0f), differenceColour(1.0f));
    EXPECT_EQ(differenceColour(-1.0f), differenceColour(0.0f));
    EXPECT_EQ(differenceColour(0.125f), (Colour{44, 8, 57}));  // halfway between the first two stops, rounded
}

// 99 pixels differ by 1/128, 2/128, ..., 99/128 in one channel (exact in float) and one
// firefly by 1000: the 99th percentile of the 100 differences is 99/128, where the
// largest is 1000.
TEST(ColourMappedDifference, ScalesByThePercentileNotTheBrightestPixel) {
    Image target{10, 10, std::vector<float>(300, 0.5f)};
    Image current = target;
    for (int p = 0; p < 99; ++p) current.rgb[3 * p + (p % 3)] += float(p + 1) / 128.0f;
    current.rgb[3 * 99 + 1] -= 1000.0f;
    ColourMappedDifference mapped = colourMappedDifference(current, target, 0.99);
    EXPECT_EQ(mapped.scale, 99.0f / 128.0f);
    auto colourAt = [&](int p) { return Colour{mapped.rgb[3 * p], mapped.rgb[3 * p + 1], mapped.rgb[3 * p + 2]}; };
    EXPECT_EQ(colourAt(99), differenceColour(1.0f));  // the firefly is clamped to the top colour
    EXPECT_EQ(colourAt(98), differenceColour(1.0f));  // 99/128: the top of the scale
    EXPECT_EQ(colourAt(49), differenceColour(50.0f / 99.0f));
    EXPECT_NE(colourAt(49), differenceColour(1.0f));  // scaled by 1000 it would be black

    EXPECT_EQ(colourMappedDifference(target, target, 0.99).scale, 0.0f);
    EXPECT_THROW(colourMappedDifference(Image{2, 1, std::vector<float>(6)}, target, 0.99), Error);
}

// When under 1 % of the pixels differ the percentile is 0, and the largest difference
// sets the scale instead, so the few that differ still show.
TEST(ColourMappedDifference, FallsBackToTheLargestWhenThePercentileIsZero) {
    Image target{10, 10, std::vector<float>(300, 0.0f)};
    Image current = target;
    current.rgb[0] = 0.25f;
    ColourMappedDifference mapped = colourMappedDifference(current, target, 0.99);
    EXPECT_EQ(mapped.scale, 0.25f);
    EXPECT_EQ((Colour{mapped.rgb[0], mapped.rgb[1], mapped.rgb[2]}), differenceColour(1.0f));
}

TEST(ColourBar, TicksGiveTheDifferencesItsEndsAndQuartersStandFor) {
    ColourBar bar = colourBar(0.8f, 101, 3);
    ASSERT_EQ(bar.ticks.size(), 5u);
    const float positions[] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(bar.ticks[i].position, positions[i]);
        EXPECT_FLOAT_EQ(bar.ticks[i].value, 0.8f * positions[i]);
    }
    ASSERT_EQ(bar.rgb.size(), 101u * 3u * 3u);
    auto column = [&](int x, int y) {
        const uint8_t* at = &bar.rgb[3 * (size_t(y) * 101 + x)];
        return Colour{at[0], at[1], at[2]};
    };
    // Column x shows the colour of x / 100 of the scale, in every row: the tick at 1/4
    // (0.2) sits over the colour of a difference of 0.2.
    EXPECT_EQ(column(0, 0), differenceColour(0.0f));
    EXPECT_EQ(column(25, 2), differenceColour(0.25f));
    EXPECT_EQ(column(100, 1), differenceColour(1.0f));
}

TEST(Base64, MatchesTheRfc4648TestVectors) {
    auto encoded = [](const std::string& text) {
        return base64(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
    };
    EXPECT_EQ(encoded(""), "");
    EXPECT_EQ(encoded("f"), "Zg==");
    EXPECT_EQ(encoded("fo"), "Zm8=");
    EXPECT_EQ(encoded("foo"), "Zm9v");
    EXPECT_EQ(encoded("foob"), "Zm9vYg==");
    EXPECT_EQ(encoded("fooba"), "Zm9vYmE=");
    EXPECT_EQ(encoded("foobar"), "Zm9vYmFy");
    const unsigned char high[] = {0xfb, 0xff};
    EXPECT_EQ(base64(high), "+/8=");
}

TEST(Base64, DecodesWhatItEncodesAndNothingElse) {
    auto decoded = [](const std::string& text) -> std::optional<std::string> {
        std::optional<std::vector<unsigned char>> bytes = decodeBase64(text);
        if (!bytes) return std::nullopt;
        return std::string(bytes->begin(), bytes->end());
    };
    for (const std::string text : {"", "f", "fo", "foo", "foob", "fooba", "foobar"}) {
        EXPECT_EQ(decoded(base64(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()))),
                  text);
    }
    std::vector<unsigned char> every(256);
    for (int i = 0; i < 256; ++i) every[i] = static_cast<unsigned char>(i);
    EXPECT_EQ(decodeBase64(base64(every)), every);
    for (const char* bad : {"Zg=", "Zg", "Z===", "Zh==", "Zm9=", "Zg==Zg==", "Zm 9", "Zm9*", "=Zm9"}) {
        EXPECT_FALSE(decodeBase64(bad)) << bad;
    }
}

TEST(ParameterTable, ShowsStartAndFittedAndTheTruthOnlyWhereKnown) {
    std::vector<ParameterFit> fits = {{"media/fog/sigma_a", {0.3f, 0.3f, 0.3f}, {0.05f, 0.06f, 0.07f}, {}},
                                      {"media/fog/g", {0.5f}, {0.1f}, {}}};
    std::string table = parameterTable(fits);
    // Columns as wide as their widest cell, two spaces apart.
    EXPECT_EQ(table, "parameter          start        fitted\n"
                     "media/fog/sigma_a  0.3 0.3 0.3  0.05 0.06 0.07\n"
                     "media/fog/g        0.5          0.1\n");

    fits[0].truth = {0.05f, 0.05f, 0.05f};
    fits[1].truth = {0.0f};
    table = parameterTable(fits);
    EXPECT_NE(table.find("true"), std::string::npos) << table;
    EXPECT_NE(table.find("+0.00% +20.00% +40.00%"), std::string::npos) << table;
    EXPECT_NE(table.find("+0.1 abs"), std::string::npos) << table;
}

TEST(TrajectoryChart, DrawsALinePerChannelWithStartFittedAndTrueMarks) {
    ParameterTrajectory trajectory{"media/fog/sigma_a", {{0.3f, 0.3f, 0.3f}, {0.2f, 0.25f, 0.28f}}};
    ParameterFit fit{"media/fog/sigma_a", {0.3f, 0.3f, 0.3f}, {0.1f, 0.2f, 0.26f}, {0.05f, 0.05f, 0.05f}};
    std::string svg = trajectoryChartSvg(trajectory, fit);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_EQ(occurrences(svg, "<polyline"), 3u);
    EXPECT_EQ(occurrences(svg, "class=\"truth\""), 3u);
    EXPECT_EQ(occurrences(svg, "class=\"start\""), 3u);
    EXPECT_EQ(occurrences(svg, "class=\"fitted\""), 3u);
    // Each line has the two logged iterations and the fitted value after them.
    size_t points = svg.find("points=\"");
    std::string list = svg.substr(points + 8, svg.find('"', points + 8) - points - 8);
    EXPECT_EQ(std::count(list.begin(), list.end(), ','), 3) << list;

    fit.truth.clear();
    EXPECT_EQ(occurrences(trajectoryChartSvg(trajectory, fit), "class=\"truth\""), 0u);
}

TEST(ValueSummary, GivesCountMeanAndRangeAndTheRelativeL2Error) {
    const std::vector<float> values = {0.0f, 1.0f, 2.0f, 5.0f};
    ValueSummary summary = summarise(values);
    EXPECT_EQ(summary.count, 4u);
    EXPECT_DOUBLE_EQ(summary.mean, 2.0);
    EXPECT_EQ(summary.minimum, 0.0);
    EXPECT_EQ(summary.maximum, 5.0);
    EXPECT_EQ(summaryText(values), "mean 2 in [0, 5] over 4 values");
    // ||(0, 1, 2, 5) - (0, 1, 2, 3)|| / ||(0, 1, 2, 3)|| = 2 / sqrt(14).
    EXPECT_DOUBLE_EQ(*relativeL2Error(values, std::vector<float>{0.0f, 1.0f, 2.0f, 3.0f}), 2.0 / std::sqrt(14.0));
    EXPECT_FALSE(relativeL2Error(values, std::vector<float>(4, 0.0f)));
    EXPECT_FALSE(relativeL2Error(values, std::vector<float>(3, 1.0f)));
    const std::vector<double> gradient = {0.5, -3.0, 3.0, 4.0 / 3.0};
    GradientSummary gradientSummary = summariseGradient(gradient);
    EXPECT_EQ(gradientSummary.count, 4u);
    EXPECT_DOUBLE_EQ(gradientSummary.l2Norm, std::sqrt(0.25 + 9.0 + 9.0 + 16.0 / 9.0));
    EXPECT_EQ(gradientSummary.largestAt, 1u);  // the first of the two of largest magnitude
    EXPECT_EQ(gradientSummary.largest, -3.0);
    EXPECT_FALSE(isSummarised(kMostValuesListed));
    EXPECT_TRUE(isSummarised(kMostValuesListed + 1));
}

// A grid's summaries are reduced over blocks in parallel; they must still be a grid's
// summaries: the first of tied largest magnitudes, sums as one loop gives them (to
// rounding), and the same bits every time.
TEST(ValueSummary, SummarisesAGridOfManyBlocksAsOneLoopWould) {
    const size_t count = 1'000'003;  // many blocks, the last one partial
    std::vector<float> values(count), truth(count);
    std::vector<double> gradient(count);
    for (size_t i = 0; i < count; ++i) {
        values[i] = float((i * 7919) % 1000) / 100.0f;
        truth[i] = values[i] + float(i % 3) - 1.0f;
        gradient[i] = std::sin(double(i));
    }
    gradient[123'456] = -5.0;  // tied in magnitude with the later ones, in an earlier block
    gradient[700'000] = 5.0;
    gradient[999'999] = -5.0;
    long double sum = 0.0L, squares = 0.0L, error = 0.0L, norm = 0.0L;
    for (size_t i = 0; i < count; ++i) {
        sum += values[i];
        squares += gradient[i] * gradient[i];
        const long double difference = (long double)values[i] - (long double)truth[i];
        error += difference * difference;
        norm += (long double)truth[i] * truth[i];
    }
    const ValueSummary summary = summarise(values);
    EXPECT_EQ(summary.count, count);
    EXPECT_NEAR(summary.mean, double(sum / count), 1e-12 * double(sum / count));
    EXPECT_EQ(summary.minimum, 0.0);
    EXPECT_EQ(summary.maximum, 9.99f);
    const GradientSummary gradientSummary = summariseGradient(gradient);
    EXPECT_EQ(gradientSummary.largestAt, 123'456u);
    EXPECT_EQ(gradientSummary.largest, -5.0);
    EXPECT_NEAR(gradientSummary.l2Norm, std::sqrt(double(squares)), 1e-12 * std::sqrt(double(squares)));
    EXPECT_NEAR(*relativeL2Error(values, truth), std::sqrt(double(error / norm)), 1e-12);
    for (int repeat = 0; repeat < 3; ++repeat) {
        EXPECT_EQ(summarise(values).mean, summary.mean);
        EXPECT_EQ(summariseGradient(gradient).l2Norm, gradientSummary.l2Norm);
    }
}

TEST(ParameterTable, SummarisesAParameterOfManyValuesWithItsRelativeError) {
    std::vector<float> truth(64, 1.0f), fitted(64, 1.0f);
    fitted[0] = 9.0f;  // ||fitted - truth|| = 8, ||truth|| = 8
    std::vector<ParameterFit> fits = {{"media/smoke/density", std::vector<float>(64, 0.5f), fitted, truth}};
    std::string table = parameterTable(fits);
    EXPECT_NE(table.find("mean 0.5 in [0.5, 0.5] over 64 values"), std::string::npos) << table;
    EXPECT_NE(table.find("mean 1.125 in [1, 9] over 64 values"), std::string::npos) << table;
    EXPECT_NE(table.find("relative L2 error 100.00%"), std::string::npos) << table;
}

// A true grid of zeros: the error is absolute, as for a single value whose truth is 0.
TEST(ParameterTable, GivesTheAbsoluteErrorOfManyValuesWhoseTruthIsZero) {
    std::vector<float> fitted(64, 0.0f);
    fitted[0] = 16.0f;  // RMS sqrt(256 / 64) = 2
    std::vector<ParameterFit> fits = {{"media/smoke/density", std::vector<float>(64, 0.5f), fitted,
                                       std::vector<float>(64, 0.0f)}};
    std::string table = parameterTable(fits);
    EXPECT_NE(table.find("RMS error 2 abs"), std::string::npos) << table;
}

TEST(TrajectoryChart, DrawsTheSmallestMeanAndLargestOfASummarisedParameter) {
    ParameterTrajectory trajectory{"media/smoke/density", {}, {{64, 0.5, 0.5, 0.5}, {64, 0.6, 0.1, 2.0}}};
    ParameterFit fit{"media/smoke/density", std::vector<float>(64, 0.5f), std::vector<float>(64, 0.7f),
                     std::vector<float>(64, 0.8f)};
    std::string svg = trajectoryChartSvg(trajectory, fit);
    EXPECT_EQ(occurrences(svg, "<polyline"), 3u);
    EXPECT_EQ(occurrences(svg, "class=\"truth\""), 3u);
    EXPECT_NE(svg.find("smallest, mean, largest"), std::string::npos);
    size_t points = svg.find("points=\"");
    std::string list = svg.substr(points + 8, svg.find('"', points + 8) - points - 8);
    EXPECT_EQ(std::count(list.begin(), list.end(), ','), 3) << list;  // two iterations and the fitted value
}

TEST(MetricChart, DrawsEveryFiniteValueAndAZeroLineWhereTheRangeCrossesIt) {
    MetricSeries metric{"excess", {3.0, std::nan(""), -1.0, 0.5}};
    std::string svg = metricChartSvg(metric);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    size_t points = svg.find("points=\"");
    std::string list = svg.substr(points + 8, svg.find('"', points + 8) - points - 8);
    EXPECT_EQ(std::count(list.begin(), list.end(), ','), 3) << list;
    EXPECT_EQ(occurrences(svg, "class=\"zero\""), 1u);
    EXPECT_EQ(occurrences(metricChartSvg({"error", {0.5, 0.25}}), "class=\"zero\""), 0u);
}

// A run of one iteration has one value: a line through it alone would show nothing.
TEST(MetricChart, ALoneValueIsADot) {
    EXPECT_EQ(occurrences(metricChartSvg({"error", {0.5}}), "<circle"), 1u);
    EXPECT_EQ(occurrences(metricChartSvg({"error", {0.5, std::nan("")}}), "<circle"), 1u);
    EXPECT_EQ(occurrences(metricChartSvg({"error", {0.5, 0.25}}), "<circle"), 0u);
    EXPECT_EQ(occurrences(lossChartSvg(std::vector<double>{0.1}, "l2"), "<circle"), 1u);
}

}  // namespace
}  // namespace vkdr::test
