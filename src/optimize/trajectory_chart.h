#pragma once
#include <string>

#include "optimize/iteration_log.h"
#include "optimize/parameter_table.h"

namespace vkdr {

// A small SVG line chart of one parameter through a run: each channel's value per
// iteration (red, green and blue lines for an RGB parameter, one line otherwise; for a
// parameter the log summarises, its smallest, mean and largest value) on a linear axis,
// ending at the fitted value one step after the last logged iteration; dots mark the
// start and fitted values, and dashed lines the true values when known.
std::string trajectoryChartSvg(const ParameterTrajectory& trajectory, const ParameterFit& fit);

}  // namespace vkdr
