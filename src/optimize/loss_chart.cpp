#include "optimize/loss_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/format_text.h"
#include "optimize/svg_chart.h"

namespace vkdr {
namespace {

constexpr double kWidth = 480, kHeight = 300;
constexpr double kLeft = 64, kRight = 16, kTop = 16, kBottom = 44;  // margins around the plot area

// Whole decades around the positive losses, at least one decade tall.
std::pair<int, int> decadeRange(std::span<const double> losses) {
    double low = std::numeric_limits<double>::infinity(), high = 0.0;
    for (double loss : losses) {
        if (loss > 0.0 && std::isfinite(loss)) {
            low = std::min(low, loss);
            high = std::max(high, loss);
        }
    }
    if (high == 0.0) return {0, 1};
    int lowDecade = int(std::floor(std::log10(low)));
    int highDecade = std::max(int(std::ceil(std::log10(high))), lowDecade + 1);
    return {lowDecade, highDecade};
}

}  // namespace

std::string lossChartSvg(std::span<const double> losses, std::string_view lossName) {
    auto [lowDecade, highDecade] = decadeRange(losses);
    double plotWidth = kWidth - kLeft - kRight, plotHeight = kHeight - kTop - kBottom;
    double lastIteration = std::max<double>(1.0, double(losses.size()) - 1.0);
    auto x = [&](double iteration) { return kLeft + plotWidth * iteration / lastIteration; };
    auto y = [&](double loss) {
        return kTop + plotHeight * (highDecade - std::log10(loss)) / double(highDecade - lowDecade);
    };

    std::string svg = svgHeader(kWidth, kHeight);
    for (int decade = lowDecade; decade <= highDecade; ++decade) {
        double at = y(std::pow(10.0, decade));
        svg += formatText("<line x1=\"%g\" y1=\"%.2f\" x2=\"%g\" y2=\"%.2f\" stroke=\"#ddd\"/>\n", kLeft, at,
                      kWidth - kRight, at);
        svg += formatText("<text x=\"%g\" y=\"%.2f\" text-anchor=\"end\" dominant-baseline=\"middle\">1e%d</text>\n",
                      kLeft - 6, at, decade);
    }
    svg += iterationAxisSvg(kLeft, kTop, kWidth - kRight, kHeight - kBottom, lastIteration, x);
    svg += formatText("<text transform=\"translate(14 %g) rotate(-90)\" text-anchor=\"middle\">%s loss (log scale)</text>\n",
                  kTop + plotHeight / 2, std::string(lossName).c_str());

    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < losses.size(); ++i) {
        if (losses[i] > 0.0 && std::isfinite(losses[i])) points.emplace_back(x(double(i)), y(losses[i]));
    }
    return svg + seriesSvg(points) + "</svg>\n";
}

}  // namespace vkdr
