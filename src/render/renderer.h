#pragma once
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "image/image.h"
#include "render/gpu_scene.h"
#include "render/loss_kind.h"
#include "render/path_buffers.h"
#include "render/path_progress.h"
#include "render/render_settings.h"
#include "render/stage_pipelines.h"
#include "scene/parameter_kinds.h"
#include "scene/scene.h"

namespace vkdr {

class VulkanContext;
class CommandRecorder;
class DispatchTimer;

struct RenderStats {
    uint64_t paths = 0;
    uint64_t rays = 0;            // closest-hit and shadow rays traced
    uint64_t truncatedPaths = 0;  // paths cut by the segment limit (should be 0)
    double seconds = 0.0;         // wall time of render(), uploads excluded
};

// Parameter gradients as the adjoint pass accumulates them, one vector per accumulator
// of VKDR_GRADIENT_ACCUMULATORS (device_types.h): `media` has gpu::kMediumGradientStride
// values per medium, `baseColors` and `emissions` gpu::kColorGradientStride per material,
// `lights` as many per punctual light (Scene::punctualLights),
// `texels` as many per texel (textures one after another as in Scene::textures),
// `densities` one per voxel (grids one after another as in Scene::densityGrids).
struct SceneGradients {
#define VKDR_SCENE_GRADIENTS_FIELD(name, field, ...) std::vector<float> field;
    VKDR_GRADIENT_ACCUMULATORS(VKDR_SCENE_GRADIENTS_FIELD)
#undef VKDR_SCENE_GRADIENTS_FIELD
};

// The kinds of parameter whose gradients are wanted; the others come back as zeros. The
// adjoint pipelines are compiled for these kinds alone: a CPU device runs every branch
// of a shader whether or not a lane takes it, so adding gradients nobody reads would
// cost as much as if they were read (docs/performance.md). A path that meets a
// zero-valued factor (sigma_s = 0, a base colour of 0, an albedo grid's 0, a density
// grid's 0) goes on in derivative mode to find that factor's gradient
// (docs/gradients.md), which costs as much as the rest of a path; where that gradient
// is not wanted the path ends there, as in the primal pass. A wanted gradient has the
// bits it has when every kind is wanted, unless the scene has a medium that does not
// scatter, which a gradient pass samples only when sigma_s is wanted
// (RenderParams.sampleNonScatteringMedia), or a density grid, which a gradient pass
// tracks defensively only when the density is wanted
// (RenderParams.defensiveGridCollisions). Texel gradients take 216 bytes per texel of
// every texture, and density gradients 72 bytes per voxel of every grid: they are held
// only when wanted.
struct DerivativeTargets {
    uint32_t kinds = gpu::kEveryGradientKind;  // bit (1 << ParameterKind)

    static DerivativeTargets of(std::initializer_list<ParameterKind> wanted);
    void want(ParameterKind kind) { kinds |= 1u << uint32_t(kind); }
    bool wants(ParameterKind kind) const { return ((kinds >> uint32_t(kind)) & 1u) != 0; }
};

// One render with its loss and the loss's gradient (Renderer::renderWithGradients).
struct GradientEvaluation {
    Image image;  // as loss() renders it at the same seed (docs/gradients.md: not render()'s bits)
    double loss = 0.0;
    SceneGradients gradients;
    double forwardMs = 0.0;  // wall time of the passes that render the image
    double adjointMs = 0.0;  // wall time of the rest: replays, adjoint passes and losses
};

// Throws vkdr::Error naming `what` (an image adjoint, a target) unless `image` is
// width x height pixels, the render's size.
void requireImageSize(const Image& image, int width, int height, const std::string& what);

// The wavefront path tracer: uploads a scene once, then renders it pass by pass; with
// gradients enabled it also evaluates a loss against a target and back-propagates it.
class Renderer {
public:
    Renderer(const VulkanContext& context, const Scene& scene, const Bvh& bvh, const RenderSettings& settings);
    ~Renderer();

    Image render(const ProgressCallback& progress = {});
    const RenderStats& stats() const { return stats_; }
    int width() const { return int(camera_.width); }
    // Device memory held for paths in flight, the film, and (with gradients) the
    // adjoint state: it depends on the paths per pass and the image, never on the depth.
    uint64_t pathMemoryBytes() const;
    int height() const { return int(camera_.height); }

    // New values of the differentiable parameters; the geometry must be the same. Values
    // that turn on a feature the stages were compiled without (a medium that starts to
    // scatter or to emit) compile them again, once.
    void setParameters(const Scene& scene);
    void setSeed(uint32_t seed);
    // Times every later dispatch by stage, in the scopes "forward", "replay", "adjoint"
    // and "loss" (vk/dispatch_timer.h); null, the default, times nothing.
    void setDispatchTimer(DispatchTimer* timer) { timer_ = timer; }

    // Gradient support. enableGradients() allocates the adjoint state.
    // renderWithGradients() renders at the current seed and back-propagates the loss of
    // that image to the parameters. loss() renders the image renderWithGradients() would
    // at the current seed (the same random numbers and decisions) and returns its loss
    // against the target: finite differences over it share their noise.
    void enableGradients(const Image& target, LossKind loss, const DerivativeTargets& derivativeTargets = {});
    // A new target for the enabled loss, of the render's size.
    void setTarget(const Image& target);
    double loss();
    GradientEvaluation renderWithGradients(const ProgressCallback& progress = {});

    // Renders through another of the scene's cameras at the same image size, so that
    // views of one size share a renderer: its scene, its paths and its gradient sums.
    // `scene` is the one the renderer was built for (its cameras and geometry).
    void setCamera(const Scene& scene, const std::string& camera);
    // The gradients of several views' losses in one sum on the device, read back once:
    // clearGradientSum(), then renderAddingGradients() at each view's camera, target
    // and seed (each returns its image, loss and times, not its gradients), then
    // downloadGradientSum(). renderWithGradients() is the three for one view.
    void clearGradientSum();
    GradientEvaluation renderAddingGradients(const ProgressCallback& progress = {});
    SceneGradients downloadGradientSum();

    // Gradients of a loss the caller computes from render()'s image. enableImageAdjoint()
    // allocates the adjoint state without a target; backpropagate() takes dLoss/dI (one
    // RGB value per pixel) and returns dLoss/dparameters, replaying the paths with random
    // numbers independent of the image render() gives at the current seed, so that the
    // gradient carries no covariance of the image with its own derivative
    // (docs/gradients.md, "A loss of your own").
    void enableImageAdjoint(const DerivativeTargets& derivativeTargets = {});
    SceneGradients backpropagate(const Image& imageAdjoint);

    // The radiance of the path slots of the last pass, one per path in flight: after a
    // primal pass each path's L; after an adjoint pass what the replay left of it (L_rem),
    // zero but for rounding wherever the replay took the primal pass's decisions.
    std::vector<glm::vec4> pathRadiance() const;

    // Throws vkdr::Error naming `what` unless the image has the render's size.
    void requireRenderSize(const Image& image, const std::string& what) const;

private:
    enum class PassMode {
        Film,    // render and add to the film; each path's radiance stays in its slot
        Replay,  // render without adding to the film
        Adjoint, // replay in adjoint mode the paths whose radiance is in their slots
    };
    struct SampleRange {
        uint32_t first, count;
    };
    struct PassRange {
        uint32_t firstPixel, pixelCount, firstSample, samplesInPass;
    };
    void forEachPass(SampleRange samples, const std::function<void(const PassRange&)>& pass);
    void runPass(const PassRange& range, PassMode mode);
    // Copies the radiance of a pass's paths to AdjointBuffers::keptRadiance (keep), or
    // back into their slots.
    void copyKeptRadiance(const PassRange& range, bool keep);
    void recordClearFilm(CommandRecorder& recorder);
    // Records the loss stage over the film's `samples` samples (less the baseline copy
    // if asked): it leaves dLoss/dI in imageAdjoint and the loss's sum in lossSum.
    void recordLoss(CommandRecorder& recorder, uint32_t samples, uint32_t image);
    // recordLoss() in a submission of its own.
    void submitLoss(uint32_t samples, uint32_t image);
    Image downloadFilm();
    // The image of film sums read back from the device.
    Image imageOfFilm(std::span<const glm::vec4> film) const;
    // Each leaves the image in the film, dLoss/dparameters in the gradient buffers and
    // the loss of the image in lossSum, sets result's times, and reports its progress.
    void backpropagateWithReplay(GradientEvaluation& result, const ProgressCallback& progress);
    void backpropagateSplitSamples(GradientEvaluation& result, const ProgressCallback& progress);
    void backpropagateInOnePass(GradientEvaluation& result, const ProgressCallback& progress);
    // Compiles the adjoint stages for the gradients of `kinds` (bit 1 << ParameterKind) and
    // the media they meet, unless they are compiled already.
    void compileGradientPipelines(uint32_t kinds);
    // Allocates the adjoint state; keptPaths as for AdjointBuffers.
    void allocateAdjoint(const DerivativeTargets& derivativeTargets, uint64_t keptPaths);
    // Replays every sample and runs its adjoint pass, with sample points from
    // kReplayStream: independent of every image's at any seed; imageAdjoint must hold
    // dLoss/dI.
    void replayIndependentlyAndBackpropagate();
    void recordClearAccumulators(CommandRecorder& recorder);
    // A host-visible buffer of the image's pixels times `scale`, as the per-pixel vec4s
    // of the target and image-adjoint buffers, to copy from.
    Buffer perPixelStaging(const Image& image, float scale, const std::string& name) const;
    // What the adjoint state was allocated for: a loss against a target
    // (enableGradients) or a caller's image adjoint (enableImageAdjoint). Each gradient
    // call requires its own, since the two set the samples' split apart.
    enum class AdjointUse { None, Loss, ImageAdjoint };
    void requireAdjointUse(AdjointUse use, const char* call) const;
    // Reads the gradient accumulators as floats on the device (gradient_values) and
    // downloads those and `alsoDownload`.
    SceneGradients downloadGradients(std::span<const Download> alsoDownload);
    // One segment of every path alive: closest hits, free flights, vertices, shadow rays.
    void recordSegment(CommandRecorder& recorder, const PathStages& stages, const gpu::PassConstants& constants,
                       uint32_t currentRays);
    // Segments, submitted in batches, until no path has a ray left; returns the counters.
    // After each batch it reports to progress_ how many of the pass's paths have ended.
    gpu::QueueCountersData recordSegmentsUntilNoRayIsLeft(CommandRecorder& recorder, const PathStages& stages,
                                                          const gpu::PassConstants& constants);
    void uploadParams();
    SceneGradients backpropagateImageAdjoint(const Image& imageAdjoint);
    // Renders, adds the loss's gradients to the sums, and reads back the image and the
    // loss. A view `alone` clears the sums first, in the same submission as the film, and
    // reads them back with the image.
    GradientEvaluation renderAndBackpropagateLoss(bool alone, const ProgressCallback& progress);
    // Whether a gradient pass draws the two halves of each pixel's samples from
    // independent streams (RenderParams.secondStreamFrom), as the split estimator of
    // renderWithGradients() and loss() needs, or stratifies them together.
    enum class SampleHalves { Independent, Together };
    // Runs `pass`, a gradient pass (renderWithGradients, backpropagate, loss), with
    // RenderParams.sampleNonScatteringMedia and defensiveGridCollisions set as its
    // derivative targets need and the sample halves as given; render() does neither, so an image does not depend on what
    // the renderer was set up for, and all its samples stratify together.
    template <typename Pass>
    auto asGradientPass(SampleHalves halves, Pass&& pass);

    const VulkanContext& context_;
    RenderSettings settings_;
    gpu::GpuCamera camera_;
    // setCamera's cameras, placed once each: finding the medium a camera sits in tests
    // it against every triangle.
    std::map<std::string, gpu::GpuCamera> placedCameras_;
    glm::vec3 background_;
    std::vector<uint32_t> triangleOrder_;
    uint32_t mediumCount_;
    uint32_t materialCount_;
    uint32_t punctualLightCount_;
    uint32_t texelCount_;
    uint32_t voxelCount_;
    std::string gridMedia_;  // the density grid media by name, for messages
    // What the primal stages are compiled for: media only when the scene has some, tracking
    // through grids only when it has grids, gathering media's emission once a medium
    // emits, equiangular sampling once a homogeneous medium scatters.
    MediaFeatures media_;
    GpuScene scene_;
    StagePipelines pipelines_;
    std::unique_ptr<PathBuffers> paths_;
    std::unique_ptr<AdjointBuffers> adjoint_;
    AdjointUse adjointUse_ = AdjointUse::None;
    LossKind lossKind_;
    DerivativeTargets derivativeTargets_;  // what the adjoint state and pipelines were set up for
    bool inGradientPass_ = false;     // asGradientPass() is running
    bool splitHalves_ = false;        // ... with SampleHalves::Independent
    bool replayingIndependently_ = false;  // replayIndependentlyAndBackpropagate() is running
    uint32_t splitSample_ = 0;        // RenderParams.splitSample: > 0 when backpropagateInOnePass serves
    Buffer params_;
    RenderStats stats_;
    DispatchTimer* timer_ = nullptr;
    PathProgress progress_;  // of the render or gradient evaluation under way
};

}  // namespace vkdr
