#include "cli/iteration_progress.h"

#include "core/format_text.h"

namespace vkdr {

std::string metricsText(const std::vector<Metric>& metrics) {
    std::string text;
    for (const Metric& metric : metrics) text += formatText(", %s %.4g", metric.name.c_str(), metric.value);
    return text;
}

IterationProgress::IterationProgress(ProgressBar& bar, uint32_t iterations, bool resumed)
    : bar_(bar), iterations_(iterations) {
    if (!resumed) underway_ = 0;
}

std::function<void(const IterationRecord&)> IterationProgress::onIteration() {
    return [this](const IterationRecord& record) {
        underway_ = record.iteration + 1;
        status_ = formatText("iteration %u/%u loss %.4g", record.iteration + 1, iterations_, record.loss) +
                  metricsText(record.metrics);
        bar_.update(double(record.iteration + 1) / iterations_, status_);
    };
}

ProgressCallback IterationProgress::withinIteration() {
    return [this](double fraction) {
        // Evaluations after the last iteration (report.html's renders) leave the bar full.
        if (underway_ && *underway_ < iterations_) {
            bar_.update((double(*underway_) + fraction) / iterations_, status_);
        }
    };
}

}  // namespace vkdr
