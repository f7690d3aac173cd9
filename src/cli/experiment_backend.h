#pragma once
#include "optimize/experiment_run.h"
#include "render/path_progress.h"

namespace vkdr {

class VulkanContext;
struct Bvh;

// An experiment's renders and loss gradients on `context`, for a scene whose geometry is
// `bvh`'s. A view rendered a second time with the same settings (a held-out view, at
// every iteration) keeps its renderer; the targets, rendered once each, keep none. Both
// must outlive the backend. Its loss gradients report each evaluation's progress to
// `evaluationProgress` (RenderedLossGradient::reportProgress).
ExperimentBackend renderingBackend(const VulkanContext& context, const Bvh& bvh,
                                   ProgressCallback evaluationProgress = {});

}  // namespace vkdr
