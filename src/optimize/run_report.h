#pragma once
#include <vector>

#include "image/image.h"
#include "optimize/optimization_run.h"
#include "optimize/report_html.h"

namespace vkdr {

// What report.html shows of a finished run: `startImages` are the renders at the start
// values, one per view; the trajectories come from the run's log.jsonl (the whole run,
// resumed or not); `seconds` is how long this process ran.
ReportPage runReportPage(const OptimizationJob& job, const OptimizationReport& report,
                         std::vector<Image> startImages, double seconds);

}  // namespace vkdr
