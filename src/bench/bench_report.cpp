#include "bench/bench_report.h"

#include <algorithm>
#include <map>
#include <optional>
#include <span>
#include <string>

#include "core/format_text.h"

namespace vkdr {
namespace {

// The table's columns (stage names as in render/stages.h): the stages that trace paths,
// the loss and the adjoint-mode passes as a whole first, as the JSON has always listed
// them, then the rest.
constexpr const char* kStages[] = {"generate", "intersect", "medium_sample", "shade",  "shadow",
                                   "loss",     "adjoint",   "queue_prepare", "film",   "replay", "gradient_values"};
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

// The gradient's relative noise, where there is one.
std::optional<double> gradientRelativeNoise(const SceneBenchmark& s) {
    return s.gradient && s.gradient->noise ? s.gradient->noise->relativeNoise : std::nullopt;
}

std::optional<double> gradientEfficiency(const SceneBenchmark& s) {
    return s.gradient ? s.gradient->efficiency() : std::nullopt;
}

// The number, or "-" for none.
std::string cell(const char* pattern, std::optional<double> value) {
    return value ? formatText(pattern, *value) : "-";
}

// The number, or null for none.
nlohmann::ordered_json jsonValue(std::optional<double> value) {
    return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

// One row per scene: the parameter, its gradient's mean and standard error over the
// seeds, and the time of one evaluation.
std::string gradientTable(const BenchReport& report) {
    std::string out = "\nGradient of one medium parameter over seeds, at " +
                      formatText("%g", double(kGradientParameterScale)) +
                      " times its value, against a target rendered at it\n\n"
                      "| scene | parameter | seeds | mean | standard error | evaluation ms |\n"
                      "|---|---|--:|--:|--:|--:|\n";
    for (const SceneBenchmark& s : report.scenes) {
        if (!s.gradient) {
            out += "| " + s.name + " | - | - | - | - | - |\n";
            continue;
        }
        const std::optional<GradientNoise>& noise = s.gradient->noise;
        out += "| " + s.name + " | " + s.gradient->parameter + " | " + std::to_string(s.gradient->seeds) + " | " +
               (noise ? formatText("%.4g", noise->mean) + " | " + formatText("%.2g", noise->standardError)
                      : std::string("- | -")) +
               " | " + formatText("%.1f", s.gradient->evaluationMs) + " |\n";
    }
    return out;
}

// One row per scene: its density grids' voxels, those above 0, the majorant grids'
// build, and a gradient iteration of the density alone; nothing when no scene has a grid.
std::string densityGridTable(const BenchReport& report) {
    if (std::none_of(report.scenes.begin(), report.scenes.end(),
                     [](const SceneBenchmark& s) { return s.densityGrids.has_value(); })) {
        return "";
    }
    std::string out = "\nDensity grids: voxels in their boxes (what the device holds), voxels above 0, the host's "
                      "majorant grid build, and a gradient iteration of the density alone (as a grid fit runs it) "
                      "against the forward passes timed in turn with it\n\n"
                      "| scene | grid voxels | active voxels | majorant build ms | density gradient ms | "
                      "forward ms, in turn | density gradient/forward |\n"
                      "|---|--:|--:|--:|--:|--:|--:|\n";
    for (const SceneBenchmark& s : report.scenes) {
        const std::optional<DensityGridFigures>& grids = s.densityGrids;
        const std::optional<DensityGradientTimes>& density = s.densityGradient;
        out += "| " + s.name + " | " + (grids ? std::to_string(grids->voxels) : "-") + " | " +
               (grids ? std::to_string(grids->activeVoxels) : "-") + " | " +
               cell("%.2f", grids ? std::optional(grids->majorantBuildMs) : std::nullopt) + " | " +
               cell("%.1f", density ? std::optional(density->gradientMs) : std::nullopt) + " | " +
               cell("%.1f", density ? std::optional(density->forwardMs) : std::nullopt) + " | " +
               cell("%.2f", s.densityGradientToForward()) + " |\n";
    }
    return out;
}

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
           "gradient/forward | Mpaths/s | Mrays/s | noise | efficiency | gradient noise | gradient efficiency | "
           "device MiB | host MiB |\n";
    out += "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const SceneBenchmark& s : report.scenes) {
        out += "| " + s.name + " | " + std::to_string(s.triangles) + " | " + std::to_string(s.width) + "x" +
               std::to_string(s.height) + " | " + std::to_string(s.spp) + " | " + std::to_string(s.maxDepth) +
               " | " + formatText("%.2f", s.bvhBuildMs) + " | " + formatText("%.2f", s.trianglesPerSecond() * 1e-6) +
               " | " + formatText("%.1f", s.forwardMs) + " | " + formatText("%.1f", s.gradientMs) + " | " +
               formatText("%.2f", s.gradientToForward()) + " | " + formatText("%.3f", s.pathsPerSecond() * 1e-6) + " | " +
               formatText("%.3f", s.raysPerSecond() * 1e-6) + " | " +
               cell("%.4f", s.relativeNoise) + " | " +
               cell("%.3g", s.efficiency()) + " | " +
               cell("%.4f", gradientRelativeNoise(s)) + " | " + cell("%.3g", gradientEfficiency(s)) +
               " | " + formatText("%.1f", double(peakDeviceBytes(s)) / kMiB) +
               " | " + formatText("%.1f", double(s.peakHostBytes) / kMiB) + " |\n";
    }
    out += stageTable(report,
                      "GPU ms per stage (timestamp queries); adjoint is every adjoint-mode pass, replay the primal "
                      "passes it re-renders",
                      kStages, &SceneBenchmark::stagesMs);
    out += stageTable(report, "GPU ms per stage of the adjoint-mode passes (the adjoint column above, broken down)",
                      kAdjointStages, &SceneBenchmark::adjointStagesMs);
    out += gradientTable(report);
    out += densityGridTable(report);
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
        const GradientNoise* noise = s.gradient && s.gradient->noise ? &*s.gradient->noise : nullptr;
        const std::optional<DensityGridFigures>& grids = s.densityGrids;
        scenes.push_back({
            {"name", s.name},
            {"triangles", s.triangles},
            {"width", s.width},
            {"height", s.height},
            {"spp", s.spp},
            {"max_depth", s.maxDepth},
            {"bvh_build_ms", s.bvhBuildMs},
            {"bvh_triangles_per_s", s.trianglesPerSecond()},
            {"grid_voxels", grids ? ordered_json(grids->voxels) : ordered_json(nullptr)},
            {"active_voxels", grids ? ordered_json(grids->activeVoxels) : ordered_json(nullptr)},
            {"majorant_build_ms", jsonValue(grids ? std::optional(grids->majorantBuildMs) : std::nullopt)},
            {"density_gradient_ms",
             jsonValue(s.densityGradient ? std::optional(s.densityGradient->gradientMs) : std::nullopt)},
            {"density_forward_ms",
             jsonValue(s.densityGradient ? std::optional(s.densityGradient->forwardMs) : std::nullopt)},
            {"density_gradient_to_forward", jsonValue(s.densityGradientToForward())},
            {"stages_ms", stages},
            {"adjoint_stages_ms", adjointStages},
            {"forward_ms", s.forwardMs},
            {"gradient_ms", s.gradientMs},
            {"gradient_to_forward", s.gradientToForward()},
            {"paths", s.paths},
            {"rays", s.rays},
            {"paths_per_s", s.pathsPerSecond()},
            {"rays_per_s", s.raysPerSecond()},
            {"relative_noise", jsonValue(s.relativeNoise)},
            {"efficiency", jsonValue(s.efficiency())},
            {"gradient_parameter", s.gradient ? ordered_json(s.gradient->parameter) : ordered_json(nullptr)},
            {"gradient_seeds", s.gradient ? ordered_json(s.gradient->seeds) : ordered_json(nullptr)},
            {"gradient_mean", jsonValue(noise ? std::optional(noise->mean) : std::nullopt)},
            {"gradient_standard_error", jsonValue(noise ? std::optional(noise->standardError) : std::nullopt)},
            {"gradient_relative_noise", jsonValue(gradientRelativeNoise(s))},
            {"gradient_evaluation_ms", jsonValue(s.gradient ? std::optional(s.gradient->evaluationMs) : std::nullopt)},
            {"gradient_efficiency", jsonValue(gradientEfficiency(s))},
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
