#include "optimize/metric_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/format_text.h"
#include "optimize/svg_chart.h"

namespace vkdr {
namespace {

constexpr double kWidth = 480, kHeight = 240;
constexpr double kLeft = 64, kRight = 16, kTop = 16, kBottom = 40;  // margins around the plot area

std::pair<double, double> valueRange(const std::vector<double>& values) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (double value : values) {
        if (!std::isfinite(value)) continue;
        low = std::min(low, value);
        high = std::max(high, value);
    }
    return paddedRange(low, high);
}

}  // namespace

std::string metricChartSvg(const MetricSeries& metric) {
    auto [low, high] = valueRange(metric.values);
    const double plotWidth = kWidth - kLeft - kRight, plotHeight = kHeight - kTop - kBottom;
    const double lastIteration = std::max<double>(1.0, double(metric.values.size()) - 1.0);
    auto x = [&](double iteration) { return kLeft + plotWidth * iteration / lastIteration; };
    auto y = [&](double value) { return kTop + plotHeight * (high - value) / (high - low); };

    std::string svg = svgHeader(kWidth, kHeight);
    svg += valueGridSvg(kLeft, kWidth - kRight, low, high, y);
    if (low < 0.0 && high > 0.0) {
        svg += formatText("<line class=\"zero\" x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"#555\"/>\n", kLeft,
                         y(0.0), kWidth - kRight, y(0.0));
    }
    svg += iterationAxisSvg(kLeft, kTop, kWidth - kRight, kHeight - kBottom, lastIteration, x);
    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < metric.values.size(); ++i) {
        if (std::isfinite(metric.values[i])) points.emplace_back(x(double(i)), y(metric.values[i]));
    }
    return svg + seriesSvg(points) + "</svg>\n";
}

}  // namespace vkdr
