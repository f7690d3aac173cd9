// The Renderer's loss and gradient: the loss stage, and the split-sample adjoint passes
// of renderWithGradients() (docs/gradients.md, "The estimator").
#include "render/renderer.h"

#include <algorithm>

#include "core/error.h"
#include "core/fixed_point_value.h"
#include "core/milliseconds_of.h"
#include "render/push_constants.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/dispatch_timer.h"

namespace vkdr {
namespace {

// Gradient pipelines kept for kinds not wanted now: a few alternating sets of
// parameters, each a few seconds of compiling on lavapipe.
constexpr size_t kEarlierGradientPipelines = 3;

}  // namespace

DerivativeTargets DerivativeTargets::of(std::initializer_list<ParameterKind> wanted) {
    DerivativeTargets targets{0};
    for (ParameterKind kind : wanted) {
        targets.want(kind);
    }
    return targets;
}

void Renderer::enableGradients(const Image& target, LossKind loss, const DerivativeTargets& derivativeTargets) {
    requireRenderSize(target, "the target");
    const uint64_t pixels = uint64_t(camera_.width) * camera_.height;
    const bool onePass = settings_.spp >= 2 && pixels * settings_.spp <= paths_->capacity;
    splitSample_ = onePass ? settings_.spp / 2 : 0;
    // Otherwise the first half of the samples keeps its paths' radiance while the second
    // half renders (backpropagateSplitSamples), when that fits in its budget.
    const uint64_t keptPaths = onePass ? 0 : pixels * (settings_.spp / 2);
    const uint64_t keptBudget = std::min(settings_.keptRadianceBytes, context_.deviceLocalHeapBytes() / 8);
    lossKind_ = loss;
    allocateAdjoint(derivativeTargets, keptPaths * AdjointBuffers::kKeptBytesPerPath <= keptBudget ? keptPaths : 0);
    adjointUse_ = AdjointUse::Loss;
    setTarget(target);
}

void Renderer::requireAdjointUse(AdjointUse use, const char* call) const {
    if (adjointUse_ != use) {
        throw Error(std::string("internal: ") + call + " on a renderer whose gradients are enabled for " +
                    (adjointUse_ == AdjointUse::None   ? "nothing"
                     : adjointUse_ == AdjointUse::Loss ? "a loss (enableGradients)"
                                                       : "an image adjoint (enableImageAdjoint)"));
    }
}

void requireImageSize(const Image& image, int width, int height, const std::string& what) {
    if (image.width != width || image.height != height) {
        throw Error(what + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " but the render is " + std::to_string(width) + "x" + std::to_string(height));
    }
}

void Renderer::requireRenderSize(const Image& image, const std::string& what) const {
    requireImageSize(image, width(), height(), what);
}

void Renderer::setTarget(const Image& target) {
    requireAdjointUse(AdjointUse::Loss, "setTarget()");
    requireRenderSize(target, "the target");
    Buffer staging = perPixelStaging(target, 1.0f, "target (staging)");
    CommandRecorder recorder(context_);
    recorder.copy(staging, adjoint_->target, adjoint_->target.size());
    recorder.submitAndWait();
}

void Renderer::enableImageAdjoint(const DerivativeTargets& derivativeTargets) {
    splitSample_ = 0;
    allocateAdjoint(derivativeTargets, 0);
    adjointUse_ = AdjointUse::ImageAdjoint;
}

void Renderer::compileGradientPipelines(uint32_t kinds) {
    // The emission's gradient is wanted even where no medium emits yet.
    MediaFeatures media = media_;
    media.emission = media.emission || DerivativeTargets{kinds}.wants(ParameterKind::MediumEmission);
    auto matches = [&](const std::unique_ptr<GradientPipelines>& p) { return p->kinds == kinds && p->media == media; };
    if (pipelines_.gradient && matches(pipelines_.gradient)) {
        return;
    }
    std::vector<std::unique_ptr<GradientPipelines>>& earlier = pipelines_.earlierGradients;
    auto found = std::find_if(earlier.begin(), earlier.end(), matches);
    std::unique_ptr<GradientPipelines> next;
    if (found != earlier.end()) {
        next = std::move(*found);
        earlier.erase(found);
    } else {
        next = std::make_unique<GradientPipelines>(context_, kinds, media);
    }
    if (pipelines_.gradient) {
        earlier.insert(earlier.begin(), std::move(pipelines_.gradient));
        if (earlier.size() > kEarlierGradientPipelines) earlier.pop_back();
    }
    pipelines_.gradient = std::move(next);
}

void Renderer::allocateAdjoint(const DerivativeTargets& derivativeTargets, uint64_t keptPaths) {
    compileGradientPipelines(derivativeTargets.kinds);
    adjoint_.reset();  // the old state's memory is free before the new one takes its own
    const bool texels = derivativeTargets.wants(ParameterKind::BaseColorTexture);
    const bool voxels = derivativeTargets.wants(ParameterKind::Density) ||
                        derivativeTargets.wants(ParameterKind::EmissionGrid) ||
                        derivativeTargets.wants(ParameterKind::AlbedoGrid);
    const uint64_t voxelGradientBytes = uint64_t(voxelCount_) * gpu::kFixedPointWordsPerSum * 8;
    if (voxels && voxelGradientBytes > context_.deviceLocalHeapBytes() / 2) {
        throw Error("the gradients of the grids' " + std::to_string(voxelCount_) + " voxels need " +
                    std::to_string(voxelGradientBytes >> 20) + " MiB, more than half of the device's " +
                    std::to_string(context_.deviceLocalHeapBytes() >> 20) + " MiB; differentiate a coarser grid");
    }
    adjoint_ = std::make_unique<AdjointBuffers>(context_, paths_->capacity, camera_.width * camera_.height,
                                                mediumCount_, materialCount_, punctualLightCount_,
                                                texels ? texelCount_ : 0, voxels ? voxelCount_ : 0, keptPaths);
    derivativeTargets_ = derivativeTargets;
    uploadParams();
}

template <typename Pass>
auto Renderer::asGradientPass(SampleHalves halves, Pass&& pass) {
    inGradientPass_ = true;
    splitHalves_ = halves == SampleHalves::Independent;
    uploadParams();
    try {
        auto result = pass();
        inGradientPass_ = splitHalves_ = false;
        uploadParams();
        return result;
    } catch (...) {
        inGradientPass_ = splitHalves_ = false;
        uploadParams();
        throw;
    }
}

SceneGradients Renderer::backpropagate(const Image& imageAdjoint) {
    return asGradientPass(SampleHalves::Together, [&] { return backpropagateImageAdjoint(imageAdjoint); });
}

SceneGradients Renderer::backpropagateImageAdjoint(const Image& imageAdjoint) {
    requireAdjointUse(AdjointUse::ImageAdjoint, "backpropagate()");
    requireRenderSize(imageAdjoint, "the image adjoint");
    // Each path carries its pixel's dLoss/dI divided by the samples per pixel (adjoint.glsl).
    Buffer staging = perPixelStaging(imageAdjoint, 1.0f / float(settings_.spp), "image adjoint (staging)");
    stats_ = {};
    {
        CommandRecorder recorder(context_);
        recorder.copy(staging, adjoint_->imageAdjoint, staging.size());
        recorder.fill(paths_->queueCounters, 0);  // render() may not have run on this renderer yet
        recordClearAccumulators(recorder);
        recorder.submitAndWait();
    }
    replayIndependentlyAndBackpropagate();
    stats_.paths = uint64_t(camera_.width) * camera_.height * settings_.spp;
    return downloadGradients({});
}

Buffer Renderer::perPixelStaging(const Image& image, float scale, const std::string& name) const {
    std::vector<glm::vec4> perPixel(size_t(image.width) * image.height);
    for (size_t i = 0; i < perPixel.size(); ++i) {
        const float* rgb = &image.rgb[3 * i];
        perPixel[i] = glm::vec4(rgb[0] * scale, rgb[1] * scale, rgb[2] * scale, 0.0f);
    }
    return uploadVector<glm::vec4>(context_, perPixel, name);
}

void Renderer::recordClearAccumulators(CommandRecorder& recorder) {
#define VKDR_CLEAR_ACCUMULATOR(name, ...) recorder.fill(adjoint_->name.buffer, 0);
    VKDR_GRADIENT_ACCUMULATORS(VKDR_CLEAR_ACCUMULATOR)
#undef VKDR_CLEAR_ACCUMULATOR
}

SceneGradients Renderer::downloadGradients(std::span<const Download> alsoDownload) {
    // The device reads every sum as a float (gradient_values.comp) and copies those to the
    // adjoint's read-back buffer, in the order of VKDR_GRADIENT_ACCUMULATORS.
    {
        CommandRecorder recorder(context_, timer_);
        if (timer_) {
            timer_->setScope("gradient_values");
        }
        PushConstants push{params_.address(), gpu::PassConstants{}};
        recorder.dispatch(pipelines_.gradient->gradientValues,
                          std::min(adjoint_->gradientValueCount, kMaxDispatchThreads), push.bytes());
        recorder.barrier();
        recorder.copy(adjoint_->gradientValues, adjoint_->gradientValuesReadback, adjoint_->gradientValues.size());
        recorder.submitAndWait();
    }
    if (!alsoDownload.empty()) {
        downloadBuffers(context_, alsoDownload);
    }
    const float* values = static_cast<const float*>(adjoint_->gradientValuesReadback.mapped());
    SceneGradients gradients;
#define VKDR_TAKE_VALUES(name, field, ...) \
    gradients.field.assign(values + adjoint_->name.firstValue, values + adjoint_->name.firstValue + adjoint_->name.sums);
    VKDR_GRADIENT_ACCUMULATORS(VKDR_TAKE_VALUES)
#undef VKDR_TAKE_VALUES
    return gradients;
}

double Renderer::loss() {
    requireAdjointUse(AdjointUse::Loss, "loss()");
    asGradientPass(SampleHalves::Independent, [&] { return render(); });
    submitLoss(settings_.spp, gpu::kLossImageFilm);
    int64_t words[gpu::kFixedPointWordsPerSum];
    downloadBuffer(context_, adjoint_->lossSum, std::as_writable_bytes(std::span(words)));
    return fixedPointValue(words);
}

void Renderer::submitLoss(uint32_t samples, uint32_t image) {
    CommandRecorder recorder(context_, timer_);
    recordLoss(recorder, samples, image);
    recorder.submitAndWait();
}

void Renderer::recordLoss(CommandRecorder& recorder, uint32_t samples, uint32_t image) {
    gpu::PassConstants constants{0, camera_.width * camera_.height, 0, samples, 0, 0, 0, image};
    PushConstants push{params_.address(), constants};
    if (timer_) {
        timer_->setScope("loss");
    }
    recorder.fill(adjoint_->lossSum, 0);
    recorder.barrier();
    recorder.dispatch(pipelines_.gradient->loss, camera_.width * camera_.height, push.bytes());
}

void Renderer::copyKeptRadiance(const PassRange& range, bool keep) {
    // keptRadiance holds a path's radiance at sample * pixels + pixel (the slots of a pass
    // from 0), then in its second half the radiance's rounding in the same order.
    const uint64_t pixels = uint64_t(camera_.width) * camera_.height;
    const uint64_t keptOffset = (range.firstSample * pixels + range.firstPixel) * 16;
    const uint64_t roundingOffset = adjoint_->keptRadiance.size() / 2;
    const uint64_t bytes = uint64_t(range.pixelCount) * range.samplesInPass * 16;
    CommandRecorder recorder(context_);
    if (keep) {
        recorder.copyRange(paths_->radiance, 0, adjoint_->keptRadiance, keptOffset, bytes);
        recorder.copyRange(paths_->radianceRounding, 0, adjoint_->keptRadiance, roundingOffset + keptOffset, bytes);
    } else {
        recorder.copyRange(adjoint_->keptRadiance, keptOffset, paths_->radiance, 0, bytes);
        recorder.copyRange(adjoint_->keptRadiance, roundingOffset + keptOffset, paths_->radianceRounding, 0, bytes);
    }
    recorder.submitAndWait();
}

GradientEvaluation Renderer::renderWithGradients(const ProgressCallback& progress) {
    return asGradientPass(SampleHalves::Independent, [&] { return renderAndBackpropagateLoss(true, progress); });
}

void Renderer::clearGradientSum() {
    requireAdjointUse(AdjointUse::Loss, "clearGradientSum()");
    CommandRecorder recorder(context_);
    recordClearAccumulators(recorder);
    recorder.submitAndWait();
}

GradientEvaluation Renderer::renderAddingGradients(const ProgressCallback& progress) {
    return asGradientPass(SampleHalves::Independent, [&] { return renderAndBackpropagateLoss(false, progress); });
}

SceneGradients Renderer::downloadGradientSum() {
    requireAdjointUse(AdjointUse::Loss, "downloadGradientSum()");
    return downloadGradients({});
}

GradientEvaluation Renderer::renderAndBackpropagateLoss(bool alone, const ProgressCallback& progress) {
    requireAdjointUse(AdjointUse::Loss, "renderWithGradients()");
    stats_ = {};
    {
        CommandRecorder recorder(context_);
        if (alone) {
            recordClearAccumulators(recorder);
        }
        recordClearFilm(recorder);
        if (splitSample_ > 0) {
            recorder.fill(adjoint_->filmBaseline, 0);
        }
        recorder.submitAndWait();
    }
    GradientEvaluation result;
    if (splitSample_ > 0) {
        backpropagateInOnePass(result, progress);
    } else if (settings_.spp >= 2) {
        backpropagateSplitSamples(result, progress);
    } else {
        backpropagateWithReplay(result, progress);
    }
    stats_.paths = uint64_t(camera_.width) * camera_.height * settings_.spp;

    std::vector<glm::vec4> film(size_t(camera_.width) * camera_.height);
    int64_t lossWords[gpu::kFixedPointWordsPerSum];
    std::vector<Download> imageAndLoss{{&paths_->film, std::as_writable_bytes(std::span(film))},
                                       {&adjoint_->lossSum, std::as_writable_bytes(std::span(lossWords))}};
    if (alone) {
        result.gradients = downloadGradients(imageAndLoss);
    } else {
        downloadBuffers(context_, imageAndLoss);
    }
    result.image = imageOfFilm(film);
    result.loss = fixedPointValue(lossWords);
    return result;
}

// The gradient of a nonlinear loss multiplies dLoss/dI by dI/dtheta; taking both from
// the same samples would bias it by O(1/spp). So the samples are split in halves A and
// B: A's paths are differentiated at the image of B and B's at the image of A, each
// weighted by its share of the samples, which is unbiased and renders every path once.
// The film then holds the whole render.
void Renderer::backpropagateSplitSamples(GradientEvaluation& result, const ProgressCallback& progress) {
    const SampleRange a{0, settings_.spp / 2};
    const SampleRange b{a.count, settings_.spp - a.count};
    const bool keptFits = adjoint_->keptRadiance.size() > 0;
    // Every sample rendered and back-propagated; A's replayed too unless kept.
    const uint64_t pixels = uint64_t(camera_.width) * camera_.height;
    PathProgress::Job job(progress_, progress, pixels * (2 * settings_.spp + (keptFits ? 0 : a.count)));
    result.forwardMs += millisecondsOf([&] {
        forEachPass(a, [&](const PassRange& range) {
            runPass(range, PassMode::Film);
            if (keptFits) {
                copyKeptRadiance(range, true);
            }
        });
    });
    result.adjointMs += millisecondsOf([&] {
        CommandRecorder recorder(context_, timer_);
        recorder.copy(paths_->film, adjoint_->filmBaseline, paths_->film.size());
        recordLoss(recorder, a.count, gpu::kLossImageFilm);
        recorder.submitAndWait();
    });
    forEachPass(b, [&](const PassRange& range) {
        result.forwardMs += millisecondsOf([&] { runPass(range, PassMode::Film); });
        result.adjointMs += millisecondsOf([&] { runPass(range, PassMode::Adjoint); });
    });
    result.adjointMs += millisecondsOf([&] {
        submitLoss(b.count, gpu::kLossImageFilmMinusBaseline);
        forEachPass(a, [&](const PassRange& range) {
            if (keptFits) {
                copyKeptRadiance(range, false);
            } else {
                runPass(range, PassMode::Replay);
            }
            runPass(range, PassMode::Adjoint);
        });
        submitLoss(settings_.spp, gpu::kLossImageFilm);
    });
}

// When every path of the render fits in one pass, the halves render together: the film
// stage also sums the samples below splitSample_ into filmBaseline, one loss dispatch
// takes each half's dLoss/dI at the other half's image, and one adjoint pass follows
// every path. Two passes instead of backpropagateSplitSamples' four: a pass that does
// not fill a GPU costs about as much as one that does (docs/performance.md).
void Renderer::backpropagateInOnePass(GradientEvaluation& result, const ProgressCallback& progress) {
    const PassRange all{0, camera_.width * camera_.height, 0, settings_.spp};
    PathProgress::Job job(progress_, progress, 2 * uint64_t(all.pixelCount) * all.samplesInPass);
    result.forwardMs += millisecondsOf([&] { runPass(all, PassMode::Film); });
    result.adjointMs += millisecondsOf([&] {
        submitLoss(settings_.spp, gpu::kLossImageHalves);
        runPass(all, PassMode::Adjoint);
    });
}

// One sample per pixel cannot be split: dLoss/dI comes from the image, and the adjoint
// replays paths with independent random numbers.
void Renderer::backpropagateWithReplay(GradientEvaluation& result, const ProgressCallback& progress) {
    // Each sample rendered, replayed and back-propagated.
    PathProgress::Job job(progress_, progress, 3 * uint64_t(camera_.width) * camera_.height * settings_.spp);
    result.forwardMs += millisecondsOf([&] {
        forEachPass({0, settings_.spp}, [this](const PassRange& range) { runPass(range, PassMode::Film); });
    });
    result.adjointMs += millisecondsOf([&] {
        submitLoss(settings_.spp, gpu::kLossImageFilm);
        replayIndependentlyAndBackpropagate();
    });
}

void Renderer::replayIndependentlyAndBackpropagate() {
    replayingIndependently_ = true;
    uploadParams();
    try {
        forEachPass({0, settings_.spp}, [this](const PassRange& range) {
            runPass(range, PassMode::Replay);
            runPass(range, PassMode::Adjoint);
        });
    } catch (...) {
        replayingIndependently_ = false;  // an interrupted replay leaves the renderer as it found it
        uploadParams();
        throw;
    }
    replayingIndependently_ = false;
    uploadParams();
}

}  // namespace vkdr
