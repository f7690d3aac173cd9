#include "python/scene_session.h"

#include <cmath>

#include <unistd.h>

#include "core/error.h"
#include "diff/gradient_slots.h"
#include "image/finite_pixels.h"
#include "image/output_paths.h"
#include "render/camera_setup.h"
#include "scene/parameters.h"
#include "scene/scene_warnings.h"
#include "scene/write_scene.h"

namespace vkdr {
namespace {

// Renderers kept per session: each holds its paths' buffers (tens of MB at the default
// paths per pass), and a loop seldom alternates between more views than this.
constexpr size_t kCachedRenderers = 4;

bool sameView(const RenderSettings& a, const RenderSettings& b) {
    return a.camera == b.camera && a.width == b.width && a.height == b.height && a.spp == b.spp &&
           a.maxDepth == b.maxDepth && a.pathsPerPass == b.pathsPerPass &&
           a.equiangularSampling == b.equiangularSampling;
}

// `file` made absolute, so that write() finds the original after the caller changes
// directory; an empty name, which has no absolute path, is left for loadScene to refuse.
std::filesystem::path absoluteSceneFile(const std::filesystem::path& file) {
    if (file.empty()) return file;
    std::error_code error;
    std::filesystem::path absolute = std::filesystem::absolute(file, error);
    if (error) throw Error(file.string() + ": " + error.message() + " (the working directory cannot be read)");
    return absolute;
}

}  // namespace

// How a renderer's adjoint state was last set up: for a caller's image adjoint (no loss)
// or for a loss against a target, and for which derivative targets. Another set of
// targets sets it up again, a subset too: what a gradient pass samples depends on the
// kinds it differentiates (RenderParams.sampleNonScatteringMedia), so a subset would
// have other bits under a superset's set-up than alone. The renderer keeps the
// pipelines of recent sets, so a change of set costs an allocation, not a compile.
struct AdjointSetUp {
    std::optional<LossKind> loss;
    DerivativeTargets targets;
};

struct SceneSession::CachedRenderer {
    RenderSettings settings;
    std::unique_ptr<Renderer> renderer;
    uint64_t parameterVersion = 0;
    std::optional<AdjointSetUp> adjoint;  // none until a gradient is asked for
};

SceneSession::SceneSession(const std::filesystem::path& file, const std::string& device, bool allowOutsideFiles)
    : file_(absoluteSceneFile(file)),
      loaded_(loadScene(file, SceneFileAccess{allowOutsideFiles})),
      process_(getpid()) {
    warnings_ = loaded_.warnings;
    for (std::string& warning : sceneWarnings(loaded_.scene, file)) {
        warnings_.push_back(std::move(warning));
    }
    bvh_ = buildBvh(loaded_.scene.positions, loaded_.scene.triangles);
    context_ = std::make_unique<VulkanContext>(ContextOptions{device});
}

SceneSession::~SceneSession() {
    if (getpid() != process_) {
        // A forked child's copy: the device objects are the parent's, and destroying them
        // here would wait for the parent's device threads. The child's memory goes with it.
        for (CachedRenderer& cached : renderers_) static_cast<void>(cached.renderer.release());
        static_cast<void>(context_.release());
        return;
    }
    renderers_.clear();  // before the context they were made on
}

std::unique_lock<std::recursive_mutex> SceneSession::lockInOwnProcess() const {
    if (getpid() != process_) {
        throw Error("this Scene was made in another process, before a fork (a DataLoader's worker, or "
                    "multiprocessing's fork): its device stayed there; make a vkdiffrender.Scene in each process "
                    "that uses one (in a DataLoader, in its worker_init_fn)");
    }
    return std::unique_lock(mutex_);
}

std::vector<ParameterInfo> SceneSession::parameters() const {
    auto lock = lockInOwnProcess();
    std::vector<ParameterInfo> infos;
    for (const std::string& name : parameterNames(loaded_.scene)) {
        infos.push_back(parameter(name));
    }
    return infos;
}

ParameterInfo SceneSession::parameter(const std::string& name) const {
    auto lock = lockInOwnProcess();
    const size_t values = getParameter(loaded_.scene, name).size();  // throws for an unknown name
    const ParameterDescription& description = *parseParameterName(name)->description;
    ParameterInfo info{name, {description.channels}, description.range};
    if (description.kind == ParameterKind::BaseColorTexture) {
        for (const Material& material : loaded_.scene.materials) {
            if (!material.isMediumBoundary() && name == parameterName(description.kind, material.name)) {
                const Texture& texture = loaded_.scene.textures[size_t(material.baseColorTexture)];
                info.shape = {size_t(texture.height), size_t(texture.width), description.channels};
                for (const Material& other : loaded_.scene.materials) {
                    const std::string otherName = parameterName(description.kind, other.name);
                    if (!other.isMediumBoundary() && other.baseColorTexture == material.baseColorTexture &&
                        otherName != name) {
                        info.aliases.push_back(otherName);
                    }
                }
            }
        }
    }
    if (const DensityGrid* grid = densityGridOf(loaded_.scene, name)) {
        info.shape = {size_t(grid->size.z), size_t(grid->size.y), size_t(grid->size.x)};
        if (grid->channels > 1) info.shape.push_back(size_t(grid->channels));
    }
    size_t count = 1;
    for (size_t extent : info.shape) count *= extent;
    if (count != values) {
        throw Error("internal: " + name + " has " + std::to_string(values) + " values, not as its shape says");
    }
    return info;
}

std::vector<float> SceneSession::get(const std::string& name) const {
    auto lock = lockInOwnProcess();
    return getParameter(loaded_.scene, name);
}

void SceneSession::set(const std::string& name, const std::vector<float>& values) {
    auto lock = lockInOwnProcess();
    setParameter(loaded_.scene, name, values);
    ++parameterVersion_;
}

SceneSession::CachedRenderer& SceneSession::rendererFor(const RenderSettings& settings, const Image* input,
                                                       const std::string& what) {
    auto found = renderers_.begin();
    while (found != renderers_.end() && !sameView(found->settings, settings)) ++found;
    if (found == renderers_.end()) {
        // A call refused for its camera or its input's size leaves the cached views as
        // they were: it is refused before one is evicted or a renderer built.
        const gpu::GpuCamera camera = setUpCamera(loaded_.scene, settings);
        if (input != nullptr) requireImageSize(*input, int(camera.width), int(camera.height), what);
        if (renderers_.size() == kCachedRenderers) {
            renderers_.pop_back();  // its memory is free before the new renderer takes its own
        }
        renderers_.push_front(CachedRenderer{settings, std::make_unique<Renderer>(*context_, loaded_.scene, bvh_, settings),
                                             parameterVersion_, std::nullopt});
    } else {
        renderers_.splice(renderers_.begin(), renderers_, found);
    }
    CachedRenderer& cached = renderers_.front();
    if (input != nullptr) cached.renderer->requireRenderSize(*input, what);
    if (cached.parameterVersion != parameterVersion_) {
        cached.renderer->setParameters(loaded_.scene);
        cached.parameterVersion = parameterVersion_;
    }
    cached.renderer->setSeed(settings.seed);
    return cached;
}

template <typename Work>
auto SceneSession::withRenderer(CachedRenderer& cached, Work work) {
    try {
        auto result = work(cached);
        requireNoValidationMessages(*context_);
        return result;
    } catch (...) {
        // Work cut short (Ctrl-C, a device error) may leave the renderer's queues
        // mid-pass: the next call builds a fresh one.
        renderers_.pop_front();
        throw;
    }
}

SceneSession::Rendered SceneSession::render(const RenderSettings& settings) {
    auto lock = lockInOwnProcess();
    Rendered rendered = withRenderer(rendererFor(settings), [](CachedRenderer& cached) {
        Image image = cached.renderer->render();
        return Rendered{std::move(image), cached.renderer->stats().truncatedPaths};
    });
    // Accepted scenes keep every pixel finite (docs/scene-format.md); should one not be,
    // the caller gets an error, not the number.
    if (std::optional<std::string> bad = unrepresentablePixel(rendered.image)) {
        throw Error("the render's " + *bad);
    }
    return rendered;
}

SceneSession::Backpropagated SceneSession::backpropagate(const RenderSettings& settings, const Image& imageAdjoint,
                                                         const std::vector<std::string>& names) {
    auto lock = lockInOwnProcess();
    for (size_t i = 0; i < imageAdjoint.rgb.size(); ++i) {
        if (!std::isfinite(imageAdjoint.rgb[i])) {
            const size_t pixel = i / 3;
            throw Error("the image adjoint is not finite at pixel (" + std::to_string(pixel % size_t(imageAdjoint.width)) +
                        ", " + std::to_string(pixel / size_t(imageAdjoint.width)) + ")");
        }
    }
    const std::vector<GradientSlot> slots = resolveGradientSlots(loaded_.scene, names);
    CachedRenderer& view = rendererFor(settings, &imageAdjoint, "the image adjoint");
    if (slots.empty()) {
        return {};
    }
    const DerivativeTargets wanted = derivativeTargetsOf(slots);
    uint64_t cutPaths = 0;
    const SceneGradients gradients = withRenderer(view, [&](CachedRenderer& cached) {
        if (!cached.adjoint || cached.adjoint->loss || cached.adjoint->targets.kinds != wanted.kinds) {
            cached.renderer->enableImageAdjoint(wanted);
            cached.adjoint = AdjointSetUp{std::nullopt, wanted};
        }
        SceneGradients result = cached.renderer->backpropagate(imageAdjoint);
        cutPaths = cached.renderer->stats().truncatedPaths;
        return result;
    });
    return {namedGradients(slots, gradients), cutPaths};
}

SceneSession::LossGradient SceneSession::lossGradient(const RenderSettings& settings, const Image& target,
                                                      LossKind loss, const std::vector<std::string>& names) {
    auto lock = lockInOwnProcess();
    if (std::optional<std::string> bad = unrepresentablePixel(target)) {
        throw Error("the target's " + *bad);
    }
    const std::vector<GradientSlot> slots = resolveGradientSlots(loaded_.scene, names);
    const DerivativeTargets wanted = derivativeTargetsOf(slots);
    uint64_t cutPaths = 0;
    CachedRenderer& view = rendererFor(settings, &target, "the target");
    GradientEvaluation evaluation = withRenderer(view, [&](CachedRenderer& cached) {
        if (!cached.adjoint || cached.adjoint->loss != loss || cached.adjoint->targets.kinds != wanted.kinds) {
            cached.renderer->enableGradients(target, loss, wanted);
            cached.adjoint = AdjointSetUp{loss, wanted};
        } else {
            cached.renderer->setTarget(target);
        }
        GradientEvaluation result = cached.renderer->renderWithGradients();
        cutPaths = cached.renderer->stats().truncatedPaths;
        return result;
    });
    // As render() refuses such an image, and before the gradients, which it would make
    // infinite too.
    if (std::optional<std::string> bad = unrepresentablePixel(evaluation.image)) {
        throw Error("the render's " + *bad);
    }
    if (!std::isfinite(evaluation.loss)) {
        throw Error("the loss is not finite: the image and the target differ by more than a float can sum");
    }
    return {evaluation.loss, std::move(evaluation.image), namedGradients(slots, evaluation.gradients), cutPaths};
}

std::vector<ParameterGradient> SceneSession::namedGradients(const std::vector<GradientSlot>& slots,
                                                            const SceneGradients& gradients) const {
    std::vector<ParameterGradient> result;
    for (const GradientSlot& slot : slots) {
        result.push_back({slot.name, getParameter(loaded_.scene, slot.name), gatherGradient(slot, gradients)});
        for (double value : result.back().gradient) {
            if (!std::isfinite(value)) {
                throw Error("the gradient of " + slot.name + " is not finite: it exceeds float's range (a large "
                            "image adjoint, or target's difference from the image, or a parameter near 0 that "
                            "the image depends on through its inverse, as a medium's emission over sigma_t)");
            }
        }
    }
    return result;
}

void SceneSession::write(const std::filesystem::path& out) const {
    auto lock = lockInOwnProcess();
    if (out.extension() != ".gltf") {
        throw Error(out.string() + ": the scene is written as .gltf; give a path ending in .gltf");
    }
    requireOutputFile("scene", out);
    std::vector<std::filesystem::path> inputs = loaded_.externalFiles;
    inputs.push_back(file_);
    requireOutputsAreNotInputs({{"scene", out.string()}}, inputs, "a file the scene reads");
    writeSceneWithParameters(file_, loaded_.scene, out);
}

}  // namespace vkdr
