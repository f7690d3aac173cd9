#include <cstdio>

#include "bench/bench_report.h"
#include "bench/bench_scene.h"
#include "bench/host_memory.h"
#include "bench/scene_benchmark.h"
#include "cli/commands.h"
#include "cli/install_layout.h"
#include "image/output_paths.h"
#include "cli/progress_bar.h"
#include "cli/number_options.h"
#include "cli/sampling_options.h"
#include "core/interrupt.h"
#include "core/proc_memory.h"
#include "image/atomic_write.h"
#include "vk/context.h"

namespace vkdr {
namespace {

// Small enough that the default scenes run in minutes on lavapipe.
constexpr int kDefaultWidth = 256;
constexpr uint32_t kDefaultSpp = 2;

struct BenchOptions {
    std::vector<std::string> scenes;
    BenchSettings settings;
    std::string json;
    std::string scenesDirectory = shippedScenesDirectory();
    std::string device;
    SceneFileAccess access;  // --allow-outside-files
};

int runBench(BenchOptions options) {
    if (!options.json.empty()) requireOutputFile("--json", options.json);
    if (options.settings.render.width == 0 && options.settings.render.height == 0) {
        options.settings.render.width = kDefaultWidth;
    }
    if (options.scenes.empty()) {
        options.scenes = defaultBenchScenes();
    }
    std::vector<BenchSceneSource> sources;
    for (const std::string& name : options.scenes) {
        sources.push_back(resolveBenchScene(name, options.scenesDirectory));
    }
    if (!options.json.empty()) {
        std::vector<std::filesystem::path> sceneFiles;
        for (const BenchSceneSource& source : sources) {
            if (!source.file.empty()) sceneFiles.push_back(source.file);
        }
        requireOutputsAreNotInputs({{"--json", options.json}}, sceneFiles, "a scene bench reads");
    }

    VulkanContext context(ContextOptions{options.device});
    BenchReport report;
    report.device = context.description().name;
    report.driver = context.description().driver;
    report.iterations = options.settings.iterations;
    const bool deviceIsHost = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    ProgressBar bar("bench");
    for (size_t i = 0; i < sources.size(); ++i) {
        const BenchSceneSource& source = sources[i];
        if (std::optional<std::string> reason =
                whyTooLarge(source, availableHostBytes(), context.deviceLocalHeapBytes(), deviceIsHost)) {
            bar.finish();
            std::fprintf(stderr, "skipped %s: %s\n", source.name.c_str(), reason->c_str());
            report.skipped.push_back({source.name, *reason});
            continue;
        }
        auto progress = [&](double fraction) {
            bar.update((double(i) + fraction) / double(sources.size()), source.name);
        };
        progress(0.0);
        // Each scene's memory figures count what its own renderers hold.
        context.releaseKeptStagingBuffers();
        resetPeakHostResidentBytes();
        LoadedScene loaded = loadBenchScene(source, options.access);
        if (!options.json.empty()) {
            requireOutputsAreNotInputs({{"--json", options.json}}, loaded.externalFiles,
                                       "a file that scene " + source.name + " reads");
        }
        try {
            report.scenes.push_back(benchmarkScene(context, source.name, loaded.scene, options.settings, progress));
        } catch (const Error& error) {
            throw Error("scene " + source.name + ": " + error.what());
        }
    }
    bar.finish();
    requireNoValidationMessages(context);
    throwIfInterrupted();  // a signal after the last measurement: no report

    std::printf("%s", markdownTable(report).c_str());
    if (!options.json.empty()) {
        writeAtomically(options.json, [&](std::ofstream& out) { out << reportJson(report).dump(2) << "\n"; });
    }
    return 0;
}

}  // namespace

CommandAction addBenchCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "bench", "Time scenes: BVH build, GPU time per stage, forward pass and gradient iteration, memory, "
                 "and the noise per unit time of an image and of a medium parameter's gradient");
    auto options = std::make_shared<BenchOptions>();
    options->settings.render.spp = kDefaultSpp;
    command->add_option("scenes", options->scenes,
                        "cornell_fog, cornell_smoke (any NAME.gltf in --scenes-dir), room_<N> for a procedural "
                        "room of N triangles (room_10k, room_1m), plume_<N> for cornell_plume with a procedural "
                        "plume of N^3 voxels (plume_64, plume_256), or a .gltf/.glb file (default: cornell_fog "
                        "cornell_smoke plume_64 room_10k room_100k room_1m room_10m)");
    SamplingOptions sampling = addSamplingOptions(*command, options->settings.render);
    command->remove_option(sampling.seed);  // the benchmark picks its own seeds
    command->add_option("--width", options->settings.render.width,
                        "Image width in pixels (default: 256, or from --height)")
        ->transform(integerIn(1, kMaxImageSide));
    command->add_option("--height", options->settings.render.height,
                        "Image height in pixels (default: from the width and the camera's aspect ratio)")
        ->transform(integerIn(1, kMaxImageSide));
    command
        ->add_option("--iters", options->settings.iterations,
                     "Timed runs of each measurement after one warm-up; the figures are their median")
        ->default_val(options->settings.iterations)
        ->transform(integerIn(1, 1000));
    command
        ->add_option("--gradient-seeds", options->settings.gradientSeeds,
                     "Gradient evaluations, at as many seeds, for the gradient noise of a medium parameter; 0 "
                     "skips them")
        ->default_val(options->settings.gradientSeeds)
        ->transform(integerIn(0, 1000));
    command->add_option("--json", options->json, "Also write the results as JSON (see " + docReference("Performance guide", "performance.md") + ")")
        ->check(nonEmpty("a file name"));
    command->add_flag("--allow-outside-files", options->access.allowOutsideFiles,
                      "Let the scenes read buffers and images outside their own directories (absolute paths, ../)");
    command->add_option("--scenes-dir", options->scenesDirectory, "Where the shipped scenes are")
        ->default_val(options->scenesDirectory)
        ->check(nonEmpty("a directory"));
    command->add_option("--device", options->device, "Vulkan device index or part of its name (see `info`; default: the best available)")
        ->check(nonEmpty("an index or part of a name"));
    return [command, options]() { return command->parsed() ? runBench(*options) : -1; };
}

}  // namespace vkdr
