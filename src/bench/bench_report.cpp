#include "bench/bench_report.h"

#include <map>
#include <span>
#include <string>

#include "core/format_text.h"

namespace vkdr {
namespace {

// The table's columns (stage names as in render/stages.h): the stages that trace paths,
// the loss and the adjoint-mode passes as a whole first, as the JSON has always listed
// them, then the rest.
constexpr const char* kStages[] = {"generate", "intersect", "medium_sample", "shade",  "shadow",
                                   "loss",     "adjoint",   "queue_prepare", "film",   "replay"};
constexpr const char* kAdjointStages[] = {"generate", "intersect", "medium_sample", "shade", "shadow",
                                          "queue_prepare"};

double valueOr0(const std::map<std::string, double>& values, const std::string& key) {
    auto it = values.find(key);
    return it == values.end() ? 0.0 : it->second;
}

uint64_t peakDeviceBytes(const SceneBenchmark& s) {
    return s.peakDriverDeviceBytes.value_or(s.peakAllocatedDeviceBytes);
}

constexpr double kMiB = 1024.0 * 1024.0;

// A table of GPU ms per stage, a row per scene, from the breakdown `stagesMs` names.
std::string stageTable(const BenchReport& report, const std::string& title, std::span<const char* const> stages,
                       std::map<std::string, double> SceneBenchmark::*stagesMs) {
    std::string out = "\n" + title + "\n\n| scene |";
    std::string rule = "|---|";
    for (const char* stage : stages) {
        out += std::string(" ") + stage + " |";
        rule += "--:|";
    }
    out += "\n" + rule + "\n";
    for (const SceneBenchmark& s : report.scenes) {
        out += "| " + s.name + " |";
        for (const char* stage : stages) {
            out += " " + formatText("%.2f", valueOr0(s.*stagesMs, stage)) + " |";
        }
        out += "\n";
    }
    return out;
}

}  // namespace

std::string markdownTable(const BenchReport& report) {
    std::string out = "Device: " + report.device + " (" + report.driver + "), median of " +
                      std::to_string(report.iterations) + " after a warm-up\n\n";
    out += "| scene | triangles | image | spp | depth | BVH ms | BVH Mtri/s | forward ms | gradient ms | "
           "gradient/forward | Mpaths/s | Mrays/s | noise | efficiency | device MiB | host MiB |\n";
    out += "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const SceneBenchmark& s : report.scenes) {
        out += "| " + s.name + " | " + std::to_string(s.triangles) + " | " + std::to_string(s.width) + "x" +
               std::to_string(s.height) + " | " + std::to_string(s.spp) + " | " + std::to_string(s.maxDepth) +
               " | " + formatText("%.2f", s.bvhBuildMs) + " | " + formatText("%.2f", s.trianglesPerSecond() * 1e-6) +
               " | " + formatText("%.1f", s.forwardMs) + " | " + formatText("%.1f", s.gradientMs) + " | " +
               formatText("%.2f", s.gradientToForward()) + " | " + formatText("%.3f", s.pathsPerSecond() * 1e-6) + " | " +
               formatText("%.3f", s.raysPerSecond() * 1e-6) + " | " +
               (s.relativeNoise ? formatText("%.4f", *s.relativeNoise) + " | " + formatText("%.3g", s.efficiency()) : "- | -") +
               " | " + formatText("%.1f", double(peakDeviceBytes(s)) / kMiB) +
               " | " + formatText("%.1f", double(s.peakHostBytes) / kMiB) + " |\n";
    }
    out += stageTable(report,
                      "GPU ms per stage (timestamp queries); adjoint is every adjoint-mode pass, replay the primal "
                      "passes it re-renders",
                      kStages, &SceneBenchmark::stagesMs);
    out += stageTable(report, "GPU ms per stage of the adjoint-mode passes (the adjoint column above, broken down)",
                      kAdjointStages, &SceneBenchmark::adjointStagesMs);
    for (const SkippedScene& skipped : report.skipped) {
        out += "\nskipped " + skipped.name + ": " + skipped.reason + "\n";
    }
    return out;
}

nlohmann::ordered_json reportJson(const BenchReport& report) {
    using nlohmann::ordered_json;
    ordered_json scenes = ordered_json::array();
    for (const SceneBenchmark& s : report.scenes) {
        ordered_json stages = ordered_json::object();
        for (const char* stage : kStages) {
            stages[stage] = valueOr0(s.stagesMs, stage);
        }
        ordered_json adjointStages = ordered_json::object();
        for (const char* stage : kAdjointStages) {
            adjointStages[stage] = valueOr0(s.adjointStagesMs, stage);
        }
        scenes.push_back({
            {"name", s.name},
            {"triangles", s.triangles},
            {"width", s.width},
            {"height", s.height},
            {"spp", s.spp},
            {"max_depth", s.maxDepth},
            {"bvh_build_ms", s.bvhBuildMs},
            {"bvh_triangles_per_s", s.trianglesPerSecond()},
            {"stages_ms", stages},
            {"adjoint_stages_ms", adjointStages},
            {"forward_ms", s.forwardMs},
            {"gradient_ms", s.gradientMs},
            {"gradient_to_forward", s.gradientToForward()},
            {"paths", s.paths},
            {"rays", s.rays},
            {"paths_per_s", s.pathsPerSecond()},
            {"rays_per_s", s.raysPerSecond()},
            {"relative_noise", s.relativeNoise ? ordered_json(*s.relativeNoise) : ordered_json(nullptr)},
            {"efficiency", s.efficiency()},
            {"peak_device_bytes", peakDeviceBytes(s)},
            {"peak_device_source", s.peakDriverDeviceBytes ? "VK_EXT_memory_budget" : "allocations"},
            {"peak_allocated_device_bytes", s.peakAllocatedDeviceBytes},
            {"peak_host_bytes", s.peakHostBytes},
        });
    }
    ordered_json skipped = ordered_json::array();
    for (const SkippedScene& s : report.skipped) {
        skipped.push_back({{"name", s.name}, {"reason", s.reason}});
    }
    return {{"device", report.device},
            {"driver", report.driver},
            {"iterations", report.iterations},
            {"scenes", scenes},
            {"skipped", skipped}};
}

}  // namespace vkdr
