#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/progress_bar.h"
#include "optimize/optimize_loop.h"
#include "render/path_progress.h"

namespace vkdr {

// ", name value" for each metric, as the bar and the summary show them.
std::string metricsText(const std::vector<Metric>& metrics);

// optimize's bar: it moves at the end of each iteration, with the iteration's loss and
// metrics, and within an iteration as its gradient's paths end.
class IterationProgress {
public:
    // `resumed`: the run continues from a checkpoint, so the iteration under way is
    // known only from the first that ends.
    IterationProgress(ProgressBar& bar, uint32_t iterations, bool resumed);
    // For runOptimization's progress: an iteration has ended.
    std::function<void(const IterationRecord&)> onIteration();
    // For RenderedLossGradient::reportProgress: the share done of the iteration's gradient.
    ProgressCallback withinIteration();

private:
    ProgressBar& bar_;
    uint32_t iterations_;
    std::optional<uint32_t> underway_;  // the iteration whose gradient runs
    std::string status_;                // the last iteration's
};

}  // namespace vkdr
