#include <chrono>
#include <cstdio>

#include "bvh/bvh.h"
#include "cli/commands.h"
#include "image/output_paths.h"
#include "cli/progress_bar.h"
#include "cli/number_options.h"
#include "cli/sampling_options.h"
#include "cli/scene_options.h"
#include "cli/warnings.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "image/atomic_write.h"
#include "image/finite_pixels.h"
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

std::vector<NamedOutput> outputsOf(const RenderOptions& options) {
    std::vector<NamedOutput> outputs = {{"-o", options.output}};
    if (!options.png.empty()) outputs.push_back({"--png", options.png});
    return outputs;
}

// Every output checked before any work: a bad path fails at once, not after the render.
ImageFileType requireOutputs(const RenderOptions& options) {
    requireOutputFile("-o", options.output);
    std::optional<ImageFileType> type = imageFileTypeOf(options.output);
    if (!type) {
        throw Error("-o " + options.output + ": the extension sets the file type: .exr (32-bit float linear RGB) "
                    "or .png (8-bit sRGB, clamped to [0, 1])");
    }
    if (!options.png.empty()) {
        requireOutputFile("--png", options.png);
        if (imageFileTypeOf(options.png) != ImageFileType::Png) {
            throw Error("--png " + options.png + ": must end in .png");
        }
        requireDistinctOutputs(outputsOf(options));
    }
    return *type;
}

void writeImage(const std::string& file, ImageFileType type, const Image& image, PendingRenames& pending) {
    if (type == ImageFileType::Exr) {
        writeExr(file, image, &pending);
    } else {
        writePng(file, image, &pending);
    }
}

int runRender(const RenderOptions& options) {
    const ImageFileType outputType = requireOutputs(options);
    LoadedScene loaded = loadSceneWithOverrides(options.scene);
    requireOutputsAreNotInputs(outputsOf(options), loaded.externalFiles, "a file the scene reads");
    Scene& scene = loaded.scene;

    auto bvhStart = std::chrono::steady_clock::now();
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    double bvhSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - bvhStart).count();

    throwIfInterrupted();
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
    throwIfInterrupted();  // a signal after the last pass: still no output
    // Accepted inputs keep every pixel finite (docs/scene-format.md); should one not be,
    // no file gets it.
    if (std::optional<std::string> bad = unrepresentablePixel(image)) {
        throw Error("the render's " + *bad + "; nothing was written");
    }
    // The image and its preview are replaced together or not at all.
    PendingRenames pending;
    writeImage(options.output, outputType, image, pending);
    if (!options.png.empty()) {
        writePng(options.png, image, &pending);
    }
    pending.commit();
    const RenderStats& stats = renderer.stats();
    warnOfCutPaths(stats.truncatedPaths, "the render");
    std::printf("wrote %s%s%s\n", options.output.c_str(), options.png.empty() ? "" : " and ", options.png.c_str());
    std::printf("%.2f s, %.3g paths/s, %.3g rays/s\n", stats.seconds, stats.paths / stats.seconds,
                stats.rays / stats.seconds);
    return 0;
}

}  // namespace

CommandAction addRenderCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand("render", "Render a glTF scene to a linear RGB EXR or an sRGB PNG (and a PNG preview)");
    auto options = std::make_shared<RenderOptions>();
    addSceneOptions(*command, options->scene);
    command->add_option("-o,--output", options->output, "Output image; its extension sets the type: .exr (32-bit float linear RGB) or .png (8-bit sRGB, "
                        "clamped to [0, 1]). A regular file or a new name; a symbolic link is refused")->required();
    command->add_option("--png", options->png, "Also write an sRGB PNG preview (clamped to [0, 1]) to this .png file, not the -o file")
        ->check(nonEmpty("a file name"));
    addSamplingOptions(*command, options->settings);
    command->add_option("--width", options->settings.width, "Image width in pixels (default: 512, or from --height)")
        ->transform(integerIn(1, kMaxImageSide));
    command->add_option("--height", options->settings.height,
                        "Image height in pixels (default: from the width and the camera's aspect ratio)")
        ->transform(integerIn(1, kMaxImageSide));
    command->add_option("--camera", options->settings.camera, "Camera node name (default: the first camera)")
        ->check(nonEmpty("a camera's name"));
    command->add_option("--device", options->device, "Vulkan device index or part of its name (see `info`; default: the best available)")
        ->check(nonEmpty("an index or part of a name"));
    return [command, options]() { return command->parsed() ? runRender(*options) : -1; };
}

}  // namespace vkdr
