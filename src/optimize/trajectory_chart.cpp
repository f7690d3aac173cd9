#include "optimize/trajectory_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/format_text.h"
#include "optimize/svg_chart.h"

namespace vkdr {
namespace {

constexpr double kWidth = 480, kHeight = 240;
constexpr double kLeft = 64, kRight = 16, kTop = 24, kBottom = 40;  // margins around the plot area

const char* channelColour(size_t channel, size_t channels) {
    static constexpr const char* kRgb[] = {"#d62728", "#2ca02c", "#1f77b4"};
    return channels == 3 ? kRgb[channel] : "#1f77b4";
}

// The range of every value the chart shows, padded so that no line runs along an edge.
std::pair<double, double> valueRange(const ParameterTrajectory& trajectory, const ParameterFit& fit) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    auto include = [&](const std::vector<float>& values) {
        for (float value : values) {
            if (!std::isfinite(value)) continue;
            low = std::min(low, double(value));
            high = std::max(high, double(value));
        }
    };
    for (const std::vector<float>& values : trajectory.values) include(values);
    include(fit.start);
    include(fit.fitted);
    include(fit.truth);
    if (!(low <= high)) return {0.0, 1.0};
    double padding = high > low ? 0.06 * (high - low) : std::max(1e-6, 0.1 * std::abs(high));
    return {low - padding, high + padding};
}

}  // namespace

std::string trajectoryChartSvg(const ParameterTrajectory& trajectory, const ParameterFit& fit) {
    auto [low, high] = valueRange(trajectory, fit);
    const double plotWidth = kWidth - kLeft - kRight, plotHeight = kHeight - kTop - kBottom;
    const size_t steps = trajectory.values.size();  // the fitted value sits at x = steps
    auto x = [&](double iteration) { return kLeft + plotWidth * iteration / std::max<double>(1.0, double(steps)); };
    auto y = [&](double value) { return kTop + plotHeight * (high - value) / (high - low); };

    std::string svg = svgHeader(kWidth, kHeight);
    for (int tick = 0; tick <= 4; ++tick) {
        double value = low + (high - low) * tick / 4.0;
        svg += formatText("<line x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"#ddd\"/>\n", kLeft, y(value),
                         kWidth - kRight, y(value));
        svg += formatText("<text x=\"%g\" y=\"%.2f\" text-anchor=\"end\" dominant-baseline=\"middle\">%.4g</text>\n",
                         kLeft - 6, y(value), value);
    }
    svg += iterationAxisSvg(kLeft, kTop, kWidth - kRight, kHeight - kBottom, double(steps), x);
    svg += formatText("<text x=\"%g\" y=\"14\">line: value per iteration; dots: start and fitted%s</text>\n", kLeft,
                     fit.truth.empty() ? "" : "; dashed: true value");

    const size_t channels = fit.fitted.size();
    for (size_t c = 0; c < channels; ++c) {
        const char* colour = channelColour(c, channels);
        if (c < fit.truth.size()) {
            svg += formatText("<line class=\"truth\" x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"%s\" "
                             "stroke-dasharray=\"5 4\"/>\n",
                             kLeft, y(fit.truth[c]), kWidth - kRight, y(fit.truth[c]), colour);
        }
        svg += formatText("<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", colour);
        for (size_t i = 0; i < steps; ++i) {
            if (c < trajectory.values[i].size() && std::isfinite(trajectory.values[i][c])) {
                svg += formatText("%.2f,%.2f ", x(double(i)), y(trajectory.values[i][c]));
            }
        }
        svg += formatText("%.2f,%.2f\"/>\n", x(double(steps)), y(fit.fitted[c]));
        if (c < fit.start.size()) {
            svg += formatText("<circle class=\"start\" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"white\" stroke=\"%s\"/>\n",
                             x(0.0), y(fit.start[c]), colour);
        }
        svg += formatText("<circle class=\"fitted\" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"/>\n", x(double(steps)),
                         y(fit.fitted[c]), colour);
    }
    return svg + "</svg>\n";
}

}  // namespace vkdr
