#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vkdr {

// What the report's SVG charts share (optimize/loss_chart.h, optimize/trajectory_chart.h,
// optimize/metric_chart.h).

// About five round iteration numbers (1, 2 or 5 times a power of ten apart) for an axis
// of `count` iterations.
double iterationTickStep(size_t count);

// The iteration axis of a plot area from (left, top) to (right, bottom): round ticks from
// 0 to lastIteration, placed by x(iteration), the two axis lines and the title "iteration".
std::string iterationAxisSvg(double left, double top, double right, double bottom, double lastIteration,
                             const std::function<double(double)>& x);

// A linear value axis from `low` to `high`: five grid lines across the plot area, from
// `left` to `right`, placed by y(value), each labelled at the left.
std::string valueGridSvg(double left, double right, double low, double high, const std::function<double(double)>& y);

// [low, high] padded so that no line runs along an edge; [0, 1] when low > high (no
// finite value to show).
std::pair<double, double> paddedRange(double low, double high);

// A line of the charts' blue through `points` (x, y); a lone point, which a line does
// not show, as a dot too.
std::string seriesSvg(const std::vector<std::pair<double, double>>& points);

// The start of an SVG document of this size, on white, in the charts' font.
std::string svgHeader(double width, double height);

}  // namespace vkdr
