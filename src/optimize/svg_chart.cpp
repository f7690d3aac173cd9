#include "optimize/svg_chart.h"

#include <algorithm>
#include <cmath>

#include "core/format_text.h"

namespace vkdr {

double iterationTickStep(size_t count) {
    double raw = std::max(1.0, double(count) / 5.0);
    double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double multiple : {1.0, 2.0, 5.0}) {
        if (multiple * power >= raw) return multiple * power;
    }
    return 10.0 * power;
}

std::string iterationAxisSvg(double left, double top, double right, double bottom, double lastIteration,
                             const std::function<double(double)>& x) {
    std::string svg;
    double step = iterationTickStep(size_t(lastIteration) + 1);
    for (double iteration = 0.0; iteration <= lastIteration; iteration += step) {
        svg += formatText("<text x=\"%.2f\" y=\"%g\" text-anchor=\"middle\">%g</text>\n", x(iteration), bottom + 16,
                         iteration);
    }
    svg += formatText("<path d=\"M%g %g V%g H%g\" fill=\"none\" stroke=\"black\"/>\n", left, top, bottom, right);
    svg += formatText("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">iteration</text>\n", (left + right) / 2,
                     bottom + 35);
    return svg;
}

std::string valueGridSvg(double left, double right, double low, double high, const std::function<double(double)>& y) {
    std::string svg;
    for (int tick = 0; tick <= 4; ++tick) {
        double value = low + (high - low) * tick / 4.0;
        svg += formatText("<line x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"#ddd\"/>\n", left, y(value),
                         right, y(value));
        svg += formatText("<text x=\"%g\" y=\"%.2f\" text-anchor=\"end\" dominant-baseline=\"middle\">%.4g</text>\n",
                         left - 6, y(value), value);
    }
    return svg;
}

std::pair<double, double> paddedRange(double low, double high) {
    if (!(low <= high)) return {0.0, 1.0};
    double padding = high > low ? 0.06 * (high - low) : std::max(1e-6, 0.1 * std::abs(high));
    return {low - padding, high + padding};
}

std::string seriesSvg(const std::vector<std::pair<double, double>>& points) {
    std::string svg = "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.5\" points=\"";
    for (size_t i = 0; i < points.size(); ++i) {
        svg += formatText("%s%.2f,%.2f", i == 0 ? "" : " ", points[i].first, points[i].second);
    }
    svg += "\"/>\n";
    if (points.size() == 1) {
        svg += formatText("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"#1f77b4\"/>\n", points[0].first,
                          points[0].second);
    }
    return svg;
}

std::string svgHeader(double width, double height) {
    return formatText("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" viewBox=\"0 0 %g %g\" "
                     "font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%%\" height=\"100%%\" "
                     "fill=\"white\"/>\n",
                     width, height, width, height);
}

}  // namespace vkdr
