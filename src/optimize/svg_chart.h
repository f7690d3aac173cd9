#pragma once
#include <functional>
#include <string>

namespace vkdr {

// What the report's SVG charts share (optimize/loss_chart.h, optimize/trajectory_chart.h).

// About five round iteration numbers (1, 2 or 5 times a power of ten apart) for an axis
// of `count` iterations.
double iterationTickStep(size_t count);

// The iteration axis of a plot area from (left, top) to (right, bottom): round ticks from
// 0 to lastIteration, placed by x(iteration), the two axis lines and the title "iteration".
std::string iterationAxisSvg(double left, double top, double right, double bottom, double lastIteration,
                             const std::function<double(double)>& x);

// The start of an SVG document of this size, on white, in the charts' font.
std::string svgHeader(double width, double height);

}  // namespace vkdr
