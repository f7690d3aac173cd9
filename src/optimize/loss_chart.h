#pragma once
#include <span>
#include <string>
#include <string_view>

namespace vkdr {

// A small SVG line chart of the loss per iteration: a <polyline> on a log-scale y axis
// spanning whole decades, axes labelled "iteration" and `lossName`. Losses <= 0 (or not
// finite) cannot be placed on a log scale and are left out of the line.
std::string lossChartSvg(std::span<const double> losses, std::string_view lossName);

}  // namespace vkdr
