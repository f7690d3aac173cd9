#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/setting_names.h"
#include "render/camera_setup.h"
#include "render/push_constants.h"
#include "scene/scene_medium_emission.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/dispatch_timer.h"

namespace vkdr {
namespace {

// A scene-wide medium that emits beyond what it attenuates renders infinite or past
// float: refused, naming the medium, whether the scene was loaded so or its parameters
// were set so (by a caller or an optimiser's step).
void requireBoundedSceneEmission(const Scene& scene) {
    if (std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(scene)) {
        throw Error(unbounded->problem);
    }
}

// One thread per path in a 1D dispatch of at most 65535 workgroups of 64.
constexpr uint64_t kMaxPathsPerPass = 1u << 21;
// Paths in flight per pass unless the user says otherwise. A GPU pays a fixed cost per
// pass (host round trips, barriers between short dispatches), which wider passes share
// (docs/performance.md). A CPU device gains nothing from wider passes, only memory.
uint64_t defaultPathsPerPass(const VulkanContext& context) {
    return context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1u << 20 : kMaxPathsPerPass;
}
// Segments recorded before the host looks whether any path is still alive, and whether
// a signal asks it to stop (core/interrupt.h). A GPU runs a segment of a wide pass in
// milliseconds and saves round trips by batching; a CPU device takes up to a second for
// one, and would leave a signal unanswered for several.
uint32_t segmentsPerBatch(const VulkanContext& context) {
    return context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 : 8;
}

// Pass-through boundaries add segments without adding depth; the limit only guards
// against a path caught between boundaries by round-off.
uint32_t segmentLimit(uint32_t maxDepth) {
    return 4 * (maxDepth + 1) + 64;
}

// Saturates: a count that does not fit is refused where it is used (path_buffers.cpp).
uint32_t totalTexels(const Scene& scene) {
    uint64_t count = 0;
    for (const Texture& texture : scene.textures) {
        count += texture.texels.size();
    }
    return static_cast<uint32_t>(std::min<uint64_t>(count, UINT32_MAX));
}

// The values of every grid (a voxel's channels each); writeDensityGrids keeps them below 2^31.
uint32_t totalVoxels(const Scene& scene) {
    uint64_t count = 0;
    for (const SceneDensityGrid& placed : scene.densityGrids) {
        count += placed.grid.values.size();
    }
    return static_cast<uint32_t>(std::min<uint64_t>(count, UINT32_MAX));
}

// The media a message about tracking through density grids is about: 'smoke', or
// 'smoke' or 'cloud' where several media are grids.
std::string gridMediaText(const Scene& scene) {
    std::vector<std::string> names;
    for (const Medium& medium : scene.media) {
        if (medium.isHeterogeneous()) names.push_back("'" + medium.name + "'");
    }
    std::string text;
    for (size_t i = 0; i < names.size(); ++i) {
        text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    }
    return text;
}

MediaFeatures mediaFeatures(const Scene& scene, const RenderSettings& settings) {
    return {.densityGrids = !scene.densityGrids.empty(),
            .emission = scene.anyMediumEmits(),
            .emissionGrids = scene.anyMedium(&Medium::hasEmissionGrid),
            .albedoGrids = scene.anyMedium(&Medium::hasAlbedoGrid),
            .anyMedium = !scene.media.empty(),
            .equiangularSampling = settings.equiangularSampling && scene.anyMedium(&Medium::scattersHomogeneously)};
}

uint32_t bit(uint32_t queue) {
    return 1u << queue;
}

uint32_t pathCapacity(const VulkanContext& context, const RenderSettings& settings, uint64_t pixels) {
    uint64_t wanted =
        std::min(settings.pathsPerPass > 0 ? settings.pathsPerPass : defaultPathsPerPass(context), kMaxPathsPerPass);
    // Leave most of the device's memory to the scene.
    uint64_t affordable = context.deviceLocalHeapBytes() / 4 / PathBuffers::kBytesPerPath;
    uint64_t needed = pixels * settings.spp;
    return static_cast<uint32_t>(std::max<uint64_t>(1, std::min({wanted, affordable, needed})));
}

}  // namespace

Renderer::Renderer(const VulkanContext& context, const Scene& scene, const Bvh& bvh, const RenderSettings& settings)
    : context_(context),
      settings_(settings),
      camera_(setUpCamera(scene, settings)),
      background_(scene.background),
      triangleOrder_(bvh.triangleOrder),
      mediumCount_(static_cast<uint32_t>(scene.media.size())),
      materialCount_(static_cast<uint32_t>(scene.materials.size())),
      punctualLightCount_(static_cast<uint32_t>(scene.punctualLights.size())),
      texelCount_(totalTexels(scene)),
      voxelCount_(totalVoxels(scene)),
      gridMedia_(gridMediaText(scene)),
      media_(mediaFeatures(scene, settings)),
      scene_(uploadScene(context, scene, bvh)),
      pipelines_(context, media_),
      lossKind_(LossKind::L2) {
    requireBoundedSceneEmission(scene);
    if (settings.spp == 0 || settings.spp > kMaxSamplesPerPixel) {
        throw Error(settingName(Setting::Spp) + " must be in [1, " + std::to_string(kMaxSamplesPerPixel) + "], got " +
                    std::to_string(settings.spp));
    }
    uint32_t pixels = camera_.width * camera_.height;
    paths_ = std::make_unique<PathBuffers>(context, pathCapacity(context, settings, pixels), pixels);
    uploadParams();
}

Renderer::~Renderer() = default;

uint64_t Renderer::pathMemoryBytes() const {
    return paths_->deviceBytes() + (adjoint_ ? adjoint_->deviceBytes() : 0);
}

void Renderer::setParameters(const Scene& scene) {
    requireBoundedSceneEmission(scene);
    // What new values turn on (a medium that starts to emit or to scatter) is compiled in;
    // what they turn off stays, skipped at run time.
    MediaFeatures media = media_ | mediaFeatures(scene, settings_);
    if (media != media_) {
        media_ = media;
        pipelines_.primal = PathStages(context_, false, 0, media_);
        pipelines_.earlierGradients.clear();  // compiled for the media as they were
        if (pipelines_.gradient) {
            compileGradientPipelines(pipelines_.gradient->kinds);
        }
    }
    uploadSceneParameters(context_, scene, triangleOrder_, scene_);
    uploadParams();
}

void Renderer::setSeed(uint32_t seed) {
    settings_.seed = seed;
    uploadParams();
}

void Renderer::setCamera(const Scene& scene, const std::string& camera) {
    auto placed = placedCameras_.find(camera);
    if (placed == placedCameras_.end()) {
        RenderSettings settings = settings_;
        settings.camera = camera;
        settings.width = width();
        settings.height = height();
        placed = placedCameras_.emplace(camera, setUpCamera(scene, settings)).first;
    }
    camera_ = placed->second;
    settings_.camera = camera;
    uploadParams();
}

void Renderer::uploadParams() {
    gpu::RenderParams p{};
    p.camera = camera_;
    p.background = glm::vec4(background_, 0.0f);
    p.triangleVertices = scene_.triangleVertices.address();
    p.triangleUvs = scene_.triangleUvs.address();
    p.triangleInfo = scene_.triangleInfo.address();
    p.bvhNodes = scene_.bvhNodes.address();
    p.materials = scene_.materials.address();
    p.media = scene_.media.address();
    p.textures = scene_.textures.address();
    p.texels = scene_.texels.address();
    p.triangleNormals = scene_.triangleNormals.address();
    p.triangleColors = scene_.triangleColors.address();
    p.lightSources = scene_.lightSources.address();
    p.lightCdf = scene_.lightCdf.address();
    p.punctualLights = scene_.punctualLights.address();
    p.densityGrids = scene_.densityGrids.grids.address();
    p.gridValues = scene_.densityGrids.values.address();
    p.gridMajorants = scene_.densityGrids.majorants.address();
    paths_->setAddresses(p);
    p.lightCount = scene_.lightCount;
    p.sceneMedium = scene_.sceneMedium;
    p.maxDepth = settings_.maxDepth;
    p.seed = settings_.seed;
    // The halves of a split gradient estimate must be independent (docs/gradients.md);
    // render() keeps all samples in one stratified stream.
    p.secondStreamFrom = splitHalves_ ? settings_.spp / 2 : 0u;
    p.firstStream = replayingIndependently_ ? gpu::kReplayStream : gpu::kImageStream;
    p.segmentLimit = segmentLimit(settings_.maxDepth);
    p.filmScale = 1.0f / float(settings_.spp);
    if (adjoint_) {
        adjoint_->setAddresses(p);
        p.lossKind = lossKind_ == LossKind::L1 ? gpu::kLossL1 : gpu::kLossL2;
        p.lossScale = 1.0f / (3.0f * float(camera_.width * camera_.height));
        p.splitSample = splitSample_;
        p.imagePixels = camera_.width * camera_.height;
        p.sampleNonScatteringMedia =
            inGradientPass_ && derivativeTargets_.wants(ParameterKind::SigmaS) ? 1u : 0u;
        p.defensiveGridCollisions = inGradientPass_ && derivativeTargets_.wants(ParameterKind::Density) ? 1u : 0u;
    }
    overwriteBuffer(context_, params_, std::as_bytes(std::span(&p, 1)), "render params");
}

void Renderer::forEachPass(SampleRange samples, const std::function<void(const PassRange&)>& pass) {
    // A pass covers whole samples of as many pixels as fit, or several samples of every pixel.
    const uint32_t pixels = camera_.width * camera_.height;
    const uint32_t capacity = paths_->capacity;
    const uint32_t pixelsPerPass = std::min(pixels, capacity);
    const uint32_t samplesPerPass = std::max(1u, std::min(samples.count, capacity / pixels));
    const uint32_t end = samples.first + samples.count;
    for (uint32_t sample = samples.first; sample < end; sample += samplesPerPass) {
        for (uint32_t pixel = 0; pixel < pixels; pixel += pixelsPerPass) {
            pass({pixel, std::min(pixelsPerPass, pixels - pixel), sample, std::min(samplesPerPass, end - sample)});
        }
    }
}

void Renderer::recordClearFilm(CommandRecorder& recorder) {
    recorder.fill(paths_->film, 0);
    recorder.fill(paths_->queueCounters, 0);
}

Image Renderer::downloadFilm() {
    std::vector<glm::vec4> film(size_t(camera_.width) * camera_.height);
    downloadBuffer(context_, paths_->film, std::as_writable_bytes(std::span(film)));
    return imageOfFilm(film);
}

std::vector<glm::vec4> Renderer::pathRadiance() const {
    std::vector<glm::vec4> radiance(paths_->capacity);
    downloadBuffer(context_, paths_->radiance, std::as_writable_bytes(std::span(radiance)));
    return radiance;
}

Image Renderer::imageOfFilm(std::span<const glm::vec4> film) const {
    const uint32_t pixels = camera_.width * camera_.height;
    Image image;
    image.width = int(camera_.width);
    image.height = int(camera_.height);
    image.rgb.resize(size_t(pixels) * 3);
    const float scale = 1.0f / float(settings_.spp);
    for (uint32_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) {
            image.rgb[3 * i + c] = film[i][c] * scale;
        }
    }
    return image;
}

Image Renderer::render(const ProgressCallback& progress) {
    auto start = std::chrono::steady_clock::now();
    stats_ = {};
    {
        CommandRecorder recorder(context_);
        recordClearFilm(recorder);
        recorder.submitAndWait();
    }
    {
        PathProgress::Job job(progress_, progress, uint64_t(camera_.width) * camera_.height * settings_.spp);
        forEachPass({0, settings_.spp}, [this](const PassRange& range) { runPass(range, PassMode::Film); });
    }
    Image image = downloadFilm();
    stats_.paths = uint64_t(camera_.width) * camera_.height * settings_.spp;
    stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return image;
}

void Renderer::recordSegment(CommandRecorder& recorder, const PathStages& stages, const gpu::PassConstants& constants,
                             uint32_t currentRays) {
    const uint32_t nextRays = currentRays == gpu::kQueueRays0 ? gpu::kQueueRays1 : gpu::kQueueRays0;
    const Buffer& counters = paths_->queueCounters;
    auto dispatchOffset = [](uint32_t queue) {
        return offsetof(gpu::QueueCountersData, dispatch) + queue * sizeof(gpu::DispatchArgs);
    };
    PushConstants push{params_.address(), constants};
    push.pass.currentRays = currentRays;
    // Sizes a queue's indirect dispatch from its count (and clears the counts in clearMask).
    auto prepare = [&](uint32_t queue, uint32_t clearMask) {
        PushConstants p = push;
        p.pass.queueArg = queue;
        p.pass.clearMask = clearMask;
        recorder.dispatch(pipelines_.queuePrepare, 1, p.bytes());
        recorder.barrier();
    };
    auto stageAt = [&](const ComputePipeline& pipeline, size_t offset) {
        recorder.dispatchIndirect(pipeline, counters, offset, push.bytes());
        recorder.barrier();
    };
    auto stage = [&](const ComputePipeline& pipeline, uint32_t queue) { stageAt(pipeline, dispatchOffset(queue)); };
    // A stage with a pipeline for each end of the queue prepared last (queues.glsl).
    auto stageByEnd = [&](const std::optional<ComputePipeline>& front, const ComputePipeline& back) {
        auto endOffset = [](uint32_t end) {
            return offsetof(gpu::QueueCountersData, ends) + end * sizeof(gpu::DispatchArgs);
        };
        if (front) {
            stageAt(*front, endOffset(gpu::kFrontEnd));
        }
        stageAt(back, endOffset(gpu::kBackEnd));
    };
    prepare(currentRays, bit(nextRays) | bit(gpu::kQueueShade) | bit(gpu::kQueueShadow));
    stage(pipelines_.intersect, currentRays);
    stageByEnd(stages.mediumSampleInMedia, stages.mediumSampleInVacuum);
    prepare(gpu::kQueueShade, 0);
    stageByEnd(stages.shadeMedia, stages.shadeSurfaces);
    prepare(gpu::kQueueShadow, 0);
    stage(stages.shadow, gpu::kQueueShadow);
}

gpu::QueueCountersData Renderer::recordSegmentsUntilNoRayIsLeft(CommandRecorder& recorder, const PathStages& stages,
                                                                 const gpu::PassConstants& constants) {
    uint32_t currentRays = gpu::kQueueRays0;
    const uint32_t segments = segmentLimit(settings_.maxDepth);
    gpu::QueueCountersData counters{};
    const uint32_t batch = segmentsPerBatch(context_);
    for (uint32_t segment = 0; segment < segments;) {
        for (uint32_t k = 0; k < batch && segment < segments; ++k, ++segment) {
            recordSegment(recorder, stages, constants, currentRays);
            currentRays = currentRays == gpu::kQueueRays0 ? gpu::kQueueRays1 : gpu::kQueueRays0;
        }
        recorder.copy(paths_->queueCounters, paths_->countersReadback, sizeof(counters));
        recorder.submitAndWait();
        throwIfInterrupted();
        std::memcpy(&counters, paths_->countersReadback.mapped(), sizeof(counters));
        const uint32_t alive = counters.counts[currentRays] + counters.backCounts[currentRays];
        if (alive == 0) {
            break;
        }
        const uint64_t paths = uint64_t(constants.pixelCount) * constants.samplesInPass;
        progress_.passUnderway(paths - std::min<uint64_t>(alive, paths));
    }
    return counters;
}

void Renderer::runPass(const PassRange& range, PassMode mode) {
    const PathStages& stages = mode == PassMode::Adjoint ? pipelines_.gradient->adjoint : pipelines_.primal;
    gpu::PassConstants constants{range.firstPixel, range.pixelCount, range.firstSample, range.samplesInPass,
                                 gpu::kQueueRays0, 0, 0, 0};
    PushConstants push{params_.address(), constants};
    if (timer_) {
        timer_->setScope(mode == PassMode::Film ? "forward" : mode == PassMode::Replay ? "replay" : "adjoint");
    }
    CommandRecorder recorder(context_, timer_);
    recorder.dispatch(stages.generate, range.pixelCount * range.samplesInPass, push.bytes());
    recorder.barrier();
    const gpu::QueueCountersData counters = recordSegmentsUntilNoRayIsLeft(recorder, stages, constants);
    if (mode == PassMode::Film) {
        recorder.dispatch(pipelines_.film, range.pixelCount, push.bytes());
        recorder.barrier();
    }
    // Start the next pass's counts of cut paths and rays from zero.
    static_assert(offsetof(gpu::QueueCountersData, raysTraced) ==
                  offsetof(gpu::QueueCountersData, truncatedPaths) + 4);
    recorder.fillRange(paths_->queueCounters, offsetof(gpu::QueueCountersData, truncatedPaths), 8, 0);
    recorder.submitAndWait();
    stats_.rays += counters.raysTraced;
    progress_.passEnded(uint64_t(range.pixelCount) * range.samplesInPass);
    // Replays with the film's random numbers and adjoint passes trace the film's paths
    // again, which are counted once; an independent replay traces paths of its own.
    if (mode == PassMode::Film || (mode == PassMode::Replay && replayingIndependently_)) {
        stats_.truncatedPaths += counters.truncatedPaths;
    }
    if (counters.truncatedTracking > 0) {
        throw UnrenderableValuesError(std::to_string(counters.truncatedTracking) +
                                      " rays through the density grid medium " + gridMedia_ + " needed more than " +
                                      std::to_string(gpu::kMaxTransmittanceSteps) +
                                      " tracking steps for their transmittance; the medium is too dense to render "
                                      "faithfully (lower its sigma_a and sigma_s, or its density)");
    }
    if (counters.truncatedLoops > 0) {
        throw Error("internal: " + std::to_string(counters.truncatedLoops) +
                    " BVH traversals or shadow rays hit their iteration bound; the image would be wrong");
    }
}

}  // namespace vkdr
