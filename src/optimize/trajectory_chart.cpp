#include "optimize/trajectory_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/format_text.h"
#include "optimize/svg_chart.h"
#include "optimize/value_summary.h"

namespace vkdr {
namespace {

constexpr double kWidth = 480, kHeight = 240;
constexpr double kLeft = 64, kRight = 16, kTop = 24, kBottom = 40;  // margins around the plot area

// One line of the chart: a value per iteration, with its start, fitted and true values.
struct Series {
    const char* colour;
    std::vector<float> values;  // per iteration; NaN where not logged
    std::optional<float> start, fitted, truth;
};

std::optional<float> at(const std::vector<float>& values, size_t i) {
    return i < values.size() ? std::optional<float>(values[i]) : std::nullopt;
}

// A channel per line: red, green and blue for an RGB parameter, one line otherwise.
std::vector<Series> channelSeries(const ParameterTrajectory& trajectory, const ParameterFit& fit) {
    static constexpr const char* kRgb[] = {"#d62728", "#2ca02c", "#1f77b4"};
    const size_t channels = fit.fitted.size();
    std::vector<Series> series;
    for (size_t c = 0; c < channels; ++c) {
        Series line{channels == 3 ? kRgb[c] : "#1f77b4", {}, at(fit.start, c), at(fit.fitted, c), at(fit.truth, c)};
        for (const std::vector<float>& values : trajectory.values) {
            line.values.push_back(c < values.size() ? values[c] : std::nanf(""));
        }
        series.push_back(std::move(line));
    }
    return series;
}

// The smallest, mean and largest value of a parameter the log summarises.
std::vector<Series> summarySeries(const ParameterTrajectory& trajectory, const ParameterFit& fit) {
    auto statistic = [](const std::vector<float>& values, double ValueSummary::*member) -> std::optional<float> {
        if (values.empty()) return std::nullopt;
        return float(summarise(values).*member);
    };
    std::vector<Series> series;
    for (auto [member, colour] : {std::pair{&ValueSummary::minimum, "#999"}, std::pair{&ValueSummary::mean, "#1f77b4"},
                                  std::pair{&ValueSummary::maximum, "#999"}}) {
        Series line{colour, {}, statistic(fit.start, member), statistic(fit.fitted, member),
                    statistic(fit.truth, member)};
        for (const ValueSummary& summary : trajectory.summaries) line.values.push_back(float(summary.*member));
        series.push_back(std::move(line));
    }
    return series;
}

// The range of every value the chart shows, padded so that no line runs along an edge.
std::pair<double, double> valueRange(const std::vector<Series>& series) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    auto include = [&](std::optional<float> value) {
        if (!value || !std::isfinite(*value)) return;
        low = std::min(low, double(*value));
        high = std::max(high, double(*value));
    };
    for (const Series& line : series) {
        for (float value : line.values) include(value);
        include(line.start);
        include(line.fitted);
        include(line.truth);
    }
    return paddedRange(low, high);
}

}  // namespace

std::string trajectoryChartSvg(const ParameterTrajectory& trajectory, const ParameterFit& fit) {
    const bool summarised = !trajectory.summaries.empty();
    const std::vector<Series> series = summarised ? summarySeries(trajectory, fit) : channelSeries(trajectory, fit);
    auto [low, high] = valueRange(series);
    const double plotWidth = kWidth - kLeft - kRight, plotHeight = kHeight - kTop - kBottom;
    const size_t steps = summarised ? trajectory.summaries.size() : trajectory.values.size();  // fitted at x = steps
    auto x = [&](double iteration) { return kLeft + plotWidth * iteration / std::max<double>(1.0, double(steps)); };
    auto y = [&](double value) { return kTop + plotHeight * (high - value) / (high - low); };

    std::string svg = svgHeader(kWidth, kHeight);
    svg += valueGridSvg(kLeft, kWidth - kRight, low, high, y);
    svg += iterationAxisSvg(kLeft, kTop, kWidth - kRight, kHeight - kBottom, double(steps), x);
    const bool truthKnown = !fit.truth.empty();
    svg += formatText("<text x=\"%g\" y=\"14\">%s; dots: start and fitted%s</text>\n", kLeft,
                     summarised ? "lines: smallest, mean, largest" : "line: value per iteration",
                     truthKnown ? "; dashed: true value" : "");

    for (const Series& line : series) {
        if (line.truth) {
            svg += formatText("<line class=\"truth\" x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"%s\" "
                             "stroke-dasharray=\"5 4\"/>\n",
                             kLeft, y(*line.truth), kWidth - kRight, y(*line.truth), line.colour);
        }
        svg += formatText("<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", line.colour);
        for (size_t i = 0; i < steps && i < line.values.size(); ++i) {
            if (std::isfinite(line.values[i])) svg += formatText("%.2f,%.2f ", x(double(i)), y(line.values[i]));
        }
        if (line.fitted) svg += formatText("%.2f,%.2f", x(double(steps)), y(*line.fitted));
        svg += "\"/>\n";
        if (line.start) {
            svg += formatText("<circle class=\"start\" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"white\" stroke=\"%s\"/>\n",
                             x(0.0), y(*line.start), line.colour);
        }
        if (line.fitted) {
            svg += formatText("<circle class=\"fitted\" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"/>\n",
                             x(double(steps)), y(*line.fitted), line.colour);
        }
    }
    return svg + "</svg>\n";
}

}  // namespace vkdr
