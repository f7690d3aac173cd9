#include "optimize/optimization_run.h"

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "image/atomic_write.h"
#include "optimize/difference_image.h"
#include "optimize/iteration_log.h"
#include "optimize/json_numbers.h"
#include "optimize/loss_chart.h"
#include "optimize/loss_kind_text.h"
#include "scene/parameters.h"
#include "scene/write_scene.h"

namespace vkdr {
namespace {

void writeText(const std::filesystem::path& file, const std::string& text) {
    writeAtomically(file, [&](std::ofstream& stream) { stream << text; });
}

std::string parametersJson(const Scene& scene, const std::vector<std::string>& names) {
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const std::string& name : names) {
        values[name] = floatArray(getParameter(scene, name));
    }
    return values.dump(2) + "\n";
}

void createDirectory(const std::filesystem::path& directory) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error || !std::filesystem::is_directory(directory)) {
        throw Error("cannot create output directory '" + directory.string() + "': " +
                    (error ? error.message() : "a file of that name exists"));
    }
}

}  // namespace

OptimizationReport runOptimization(LossGradient& lossGradient, Scene& scene, const OptimizationJob& job,
                                   const std::function<void(uint32_t iteration, double loss)>& progress) {
    const std::filesystem::path& directory = job.outputDirectory;
    createDirectory(directory);
    IterationLog log(directory / "log.jsonl");
    OptimizeCallbacks callbacks{progress, [&](const IterationRecord& record) { log.append(record); }};

    OptimizationReport report;
    report.result = optimize(lossGradient, scene, job.options, callbacks);
    const Image& finalImage = report.result.lastImages.at(0);
    DifferenceImage difference = scaledDifference(finalImage, job.firstTarget);
    report.largestDifference = difference.largestDifference;

    writeText(directory / "params.json", parametersJson(scene, job.options.parameters));
    writeSceneWithParameters(job.sceneFile, scene, directory / "scene.gltf");
    writeExr(directory / "final.exr", finalImage);
    writePng(directory / "final.png", finalImage);
    writePng(directory / "diff.png", difference.image);
    writeText(directory / "loss.svg", lossChartSvg(report.result.losses, lossKindName(job.loss)));
    return report;
}

}  // namespace vkdr
