#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "image/atomic_write.h"
#include "optimize/optimize_loop.h"
#include "optimize/value_summary.h"

namespace vkdr {

// One line of log.jsonl: {"iteration", "loss", "parameters": {name: [values]},
// "gradients": {name: [dLoss/dvalue]}, "metrics": {name: value} (only when the record
// has any), "forward_ms", "adjoint_ms", "iteration_ms"}, no newline. A parameter of more
// values than kMostValuesListed (optimize/value_summary.h) is logged as {"count", "mean",
// "min", "max"} and its gradient as {"count", "l2_norm", "largest"} (the value of
// largest magnitude).
std::string iterationJsonLine(const IterationRecord& record);

// log.jsonl, one line per iteration. The whole file is rewritten (atomically) after
// each iteration, so that a run stopped at any point leaves a complete, parseable log
// of the iterations done; a few hundred short lines cost nothing next to a render.
// One parameter's values through a run, as log.jsonl holds them.
struct ParameterTrajectory {
    std::string name;
    std::vector<std::vector<float>> values;  // per iteration: the value it was evaluated at, before its step
    std::vector<ValueSummary> summaries;     // instead, for a parameter the log summarises
};

// The trajectories of `names` in the log `file`, one value per logged iteration. Throws
// vkdr::Error naming the file and line when a line is not an iteration's record or lacks
// one of the parameters.
std::vector<ParameterTrajectory> readTrajectories(const std::filesystem::path& file,
                                                  const std::vector<std::string>& names);

// One metric (IterationRecord::metrics) through a run, as log.jsonl holds it.
struct MetricSeries {
    std::string name;
    std::vector<double> values;  // per iteration, NaN where a line lacks it
};

// Every metric the log `file` holds, in the order the first line naming each gives.
// Throws vkdr::Error naming the file and line when a metric is not a number.
std::vector<MetricSeries> readMetrics(const std::filesystem::path& file);

// The name of a run's log in its output directory.
inline constexpr const char* kLogFileName = "log.jsonl";

// The lines of the log `file` that a run resumed with the checkpoint's `losses`, one per
// iteration done, keeps: those of the iterations done, without any after them (a stopped
// run may have logged a few past its last checkpoint). Throws vkdr::Error naming the
// file when it is missing or its lines are not that run's: out of order, missing, or
// with other losses.
std::string resumedLogLines(const std::filesystem::path& file, const std::vector<double>& losses);

class IterationLog {
public:
    // Starts a new log; the file is written at the first append.
    explicit IterationLog(std::filesystem::path file) : file_(std::move(file)) {}
    // Continues the log of a run resumed with the checkpoint's `losses`: the first append
    // rewrites the file as resumedLogLines and the new line, so that each iteration
    // appears once and the file stays as it was until then.
    IterationLog(std::filesystem::path file, const std::vector<double>& losses);
    // Adds the record's line; with `pending`, the rewritten file waits in its temporary
    // for pending->commit() (image/atomic_write.h).
    void append(const IterationRecord& record, PendingRenames* pending = nullptr);

private:
    std::filesystem::path file_;
    std::string text_;
};

}  // namespace vkdr
