#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bvh/bvh.h"
#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "cli/sampling_options.h"
#include "cli/scene_options.h"
#include "core/error.h"
#include "image/image.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace vkdr {
namespace {

struct RenderOptions {
    SceneOptions scene;
    RenderSettings settings;
    std::string output;
    std::string png;
    std::string device;
};

void requireWritableDirectory(const std::string& file, const char* option) {
    std::filesystem::path parent = std::filesystem::path(file).parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent)) {
        throw Error(std::string(option) + " " + file + ": directory " + parent.string() + " does not exist");
    }
}

int runRender(const RenderOptions& options) {
    requireWritableDirectory(options.output, "-o");
    if (!options.png.empty()) {
        requireWritableDirectory(options.png, "--png");
    }
    Scene scene = loadSceneWithOverrides(options.scene);

    auto bvhStart = std::chrono::steady_clock::now();
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    double bvhSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - bvhStart).count();

    VulkanContext context(ContextOptions{options.device});
    Renderer renderer(context, scene, bvh, options.settings);
    std::fprintf(stderr, "%s: %zu triangles (BVH %.2f s), %dx%d, %u spp, max depth %u on %s\n",
                 options.scene.file.c_str(), scene.triangles.size(), bvhSeconds, renderer.width(),
                 renderer.height(), options.settings.spp, options.settings.maxDepth,
                 context.description().name.c_str());
    ProgressBar bar("render");
    Image image = renderer.render([&](double f) { bar.update(f); });
    bar.finish();

    requireNoValidationMessages(context);
    writeExr(options.output, image);
    if (!options.png.empty()) {
        writePng(options.png, image);
    }
    const RenderStats& stats = renderer.stats();
    if (stats.truncatedPaths > 0) {
        std::fprintf(stderr, "warning: %llu paths crossed too many medium boundaries and were cut short\n",
                     static_cast<unsigned long long>(stats.truncatedPaths));
    }
    std::printf("wrote %s%s%s\n", options.output.c_str(), options.png.empty() ? "" : " and ", options.png.c_str());
    std::printf("%.2f s, %.3g paths/s, %.3g rays/s\n", stats.seconds, stats.paths / stats.seconds,
                stats.rays / stats.seconds);
    return 0;
}

}  // namespace

CommandAction addRenderCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand("render", "Render a glTF scene to a linear RGB EXR (and a PNG preview)");
    auto options = std::make_shared<RenderOptions>();
    addSceneOptions(*command, options->scene);
    command->add_option("-o,--output", options->output, "Output EXR file (32-bit float linear RGB)")->required();
    command->add_option("--png", options->png, "Also write an sRGB PNG preview (clamped to [0, 1])");
    addSamplingOptions(*command, options->settings);
    command->add_option("--width", options->settings.width, "Image width in pixels (default: 512, or from --height)")
        ->check(CLI::Range(1, 16384));
    command->add_option("--height", options->settings.height,
                        "Image height in pixels (default: from the width and the camera's aspect ratio)")
        ->check(CLI::Range(1, 16384));
    command->add_option("--camera", options->settings.camera, "Camera node name (default: the first camera)");
    command->add_option("--device", options->device, "Vulkan device index or part of its name (see `info`)");
    return [command, options]() { return command->parsed() ? runRender(*options) : -1; };
}

}  // namespace vkdr
