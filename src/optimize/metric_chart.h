#pragma once
#include <string>

#include "optimize/iteration_log.h"

namespace vkdr {

// A small SVG line chart of one metric per iteration on a linear axis (a metric may be
// negative, as an excess error is), with a line at 0 where the range crosses it.
std::string metricChartSvg(const MetricSeries& metric);

}  // namespace vkdr
