#pragma once
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"
#include "optimize/iteration_log.h"
#include "optimize/parameter_table.h"

namespace vkdr {

// The difference images scale so that the top of the colour map is this percentile of
// the pixels' differences (optimize/difference_colour_map.h).
inline constexpr double kDifferencePercentile = 0.99;

// One view of the run: its target, its render at the start values (iteration 0's) and
// its last iteration's render, all the same size.
struct ReportView {
    std::string camera;  // "" for the scene's first camera
    Image target;
    Image start;
    Image current;
};

struct ReportPage {
    std::string commandLine;                                   // as the user typed it
    std::string scene;                                         // the scene (or experiment) file
    std::vector<std::pair<std::string, std::string>> settings; // name, value; in this order
    std::vector<ReportView> views;
    std::vector<double> losses;  // per iteration, the whole run
    std::string lossName;
    std::vector<ParameterFit> fits;
    std::vector<ParameterTrajectory> trajectories;  // the same parameters, in the same order
    std::vector<MetricSeries> metrics;              // each charted after the parameters
};

// report.html: a self-contained page (no scripts, nothing fetched: images are data:
// URIs of PNGs, charts inline SVG) with the run's command, scene, settings, the
// parameter table, the loss curve, each parameter's and each metric's chart and, per
// view, the target, start, current and difference images with the colour bar of the
// difference.
std::string reportHtml(const ReportPage& page);

}  // namespace vkdr
