#include "optimize/iteration_log.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "image/atomic_write.h"
#include "image/regular_file.h"
#include "optimize/json_numbers.h"
#include "optimize/value_summary.h"

namespace vkdr {

namespace {

nlohmann::ordered_json gradientSummaryJson(const std::vector<double>& gradient) {
    const GradientSummary summary = summariseGradient(gradient);
    return {{"count", summary.count}, {"l2_norm", summary.l2Norm}, {"largest", summary.largest}};
}

ValueSummary summaryFrom(const nlohmann::json& object) {
    ValueSummary summary;
    summary.count = object.at("count").get<size_t>();
    summary.mean = object.at("mean").get<double>();
    summary.minimum = object.at("min").get<double>();
    summary.maximum = object.at("max").get<double>();
    return summary;
}

}  // namespace

std::string iterationJsonLine(const IterationRecord& record) {
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    nlohmann::ordered_json gradients = nlohmann::ordered_json::object();
    for (const ParameterGradient& parameter : record.parameters) {
        if (isSummarised(parameter.value.size())) {
            values[parameter.name] = summaryJson(summarise(parameter.value));
            gradients[parameter.name] = gradientSummaryJson(parameter.gradient);
        } else {
            values[parameter.name] = floatArray(parameter.value);
            gradients[parameter.name] = parameter.gradient;
        }
    }
    nlohmann::ordered_json line = {{"iteration", record.iteration},
                                   {"loss", record.loss},
                                   {"parameters", values},
                                   {"gradients", gradients}};
    if (!record.metrics.empty()) {
        nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
        for (const Metric& metric : record.metrics) metrics[metric.name] = metric.value;
        line["metrics"] = metrics;
    }
    line["forward_ms"] = record.forwardMs;
    line["adjoint_ms"] = record.adjointMs;
    line["iteration_ms"] = record.iterationMs;
    return line.dump();
}

std::vector<ParameterTrajectory> readTrajectories(const std::filesystem::path& file,
                                                  const std::vector<std::string>& names) {
    std::vector<ParameterTrajectory> trajectories;
    for (const std::string& name : names) trajectories.push_back({name, {}});
    std::istringstream in(readRegularFile(file));
    uint64_t lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
        const nlohmann::json* values = record.is_object() && record.contains("parameters") ? &record["parameters"] : nullptr;
        for (ParameterTrajectory& trajectory : trajectories) {
            const bool summarised = values && values->contains(trajectory.name) &&
                                    (*values)[trajectory.name].is_object();
            if (summarised) {
                try {
                    trajectory.summaries.push_back(summaryFrom((*values)[trajectory.name]));
                } catch (const nlohmann::json::exception&) {
                    throw Error(file.string() + ": line " + std::to_string(lineNumber) + ": the summary of " +
                                trajectory.name + " lacks its count, mean, min or max");
                }
                continue;
            }
            if (!values || !values->contains(trajectory.name) || !(*values)[trajectory.name].is_array()) {
                throw Error(file.string() + ": line " + std::to_string(lineNumber) + " has no values of " +
                            trajectory.name);
            }
            std::vector<float> value;
            for (const nlohmann::json& number : (*values)[trajectory.name]) {
                if (!number.is_number()) {
                    throw Error(file.string() + ": line " + std::to_string(lineNumber) + ": " + trajectory.name +
                                " holds something other than numbers");
                }
                value.push_back(number.get<float>());
            }
            trajectory.values.push_back(std::move(value));
        }
    }
    return trajectories;
}

std::vector<MetricSeries> readMetrics(const std::filesystem::path& file) {
    std::vector<MetricSeries> series;
    std::istringstream in(readRegularFile(file));
    size_t lineNumber = 0;
    for (std::string line; std::getline(in, line); ++lineNumber) {
        nlohmann::ordered_json record = nlohmann::ordered_json::parse(line, nullptr, false);
        if (!record.is_object() || !record.contains("metrics") || !record["metrics"].is_object()) continue;
        for (const auto& [name, value] : record["metrics"].items()) {
            if (!value.is_number()) {
                throw Error(file.string() + ": line " + std::to_string(lineNumber + 1) + ": metric " + name +
                            " is not a number");
            }
            auto found = std::find_if(series.begin(), series.end(),
                                      [&](const MetricSeries& metric) { return metric.name == name; });
            if (found == series.end()) {
                series.push_back({name, {}});
                found = series.end() - 1;
            }
            found->values.resize(lineNumber, std::nan(""));
            found->values.push_back(value.get<double>());
        }
    }
    for (MetricSeries& metric : series) metric.values.resize(lineNumber, std::nan(""));
    return series;
}

std::string resumedLogLines(const std::filesystem::path& file, const std::vector<double>& losses) {
    const std::string name = file.string();
    auto fail = [&](const std::string& problem) {
        throw Error(name + ": " + problem + "; it is not the log of the run the checkpoint holds");
    };
    if (std::string reason = notRegularFileReason(file); !reason.empty()) fail(reason);
    std::istringstream in(readRegularFile(file));
    // One run logs iterations 0, 1, 2, ... in order; it may have logged some past its
    // last checkpoint, which are dropped.
    std::string kept;
    uint64_t lineNumber = 0;
    for (std::string line; std::getline(in, line) && lineNumber < losses.size(); ++lineNumber) {
        nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
        const std::string at = "line " + std::to_string(lineNumber + 1);
        bool wellFormed = record.is_object() && record.contains("iteration") && record["iteration"].is_number_unsigned() &&
                          record.contains("loss") && record["loss"].is_number();
        if (!wellFormed) fail(at + " is not an iteration's record");
        uint64_t iteration = record["iteration"].get<uint64_t>();
        if (iteration != lineNumber) {
            fail(at + " is iteration " + std::to_string(iteration) + " where " + std::to_string(lineNumber) +
                 " was expected");
        }
        double loss = record["loss"].get<double>();
        if (loss != losses[lineNumber]) {
            fail(at + ": iteration " + std::to_string(iteration) + " has loss " + nlohmann::json(loss).dump() +
                 ", the checkpoint " + nlohmann::json(losses[lineNumber]).dump());
        }
        kept += line + "\n";
    }
    if (lineNumber < losses.size()) {
        fail("it has " + std::to_string(lineNumber) + " iterations, the checkpoint " + std::to_string(losses.size()));
    }
    return kept;
}

IterationLog::IterationLog(std::filesystem::path file, const std::vector<double>& losses)
    : file_(std::move(file)), text_(resumedLogLines(file_, losses)) {}

void IterationLog::append(const IterationRecord& record, PendingRenames* pending) {
    text_ += iterationJsonLine(record) + "\n";
    writeAtomically(file_, [&](std::ofstream& stream) { stream << text_; }, pending);
}

}  // namespace vkdr
