#include "render/stage_pipelines.h"

#include <cassert>
#include <vector>

#include "render/push_constants.h"
#include "vkdr_shaders.h"

namespace vkdr {

std::span<const uint32_t> stageSpirv(Stage stage) {
    switch (stage) {
    case Stage::Generate: return spirv::generateSpirv();
    case Stage::Intersect: return spirv::intersectSpirv();
    case Stage::MediumSample: return spirv::mediumSampleSpirv();
    case Stage::Shade: return spirv::shadeSpirv();
    case Stage::Shadow: return spirv::shadowSpirv();
    case Stage::QueuePrepare: return spirv::queuePrepareSpirv();
    case Stage::Film: return spirv::filmSpirv();
    case Stage::Loss: return spirv::lossSpirv();
    }
    return {};
}

namespace {

// The pipeline of a stage; of a stage with an adjoint variant, the primal or the adjoint one
// (specialization constant 0 of shaders/lib/stage_common.glsl). The dispatch timer's
// scope, not the name, tells the variants apart.
ComputePipeline stagePipeline(const VulkanContext& context, Stage stage, bool adjoint = false) {
    const StageInfo& info = stageInfo(stage);
    assert(info.hasAdjointVariant || !adjoint);
    std::vector<uint32_t> specialization;
    if (info.hasAdjointVariant) {
        specialization.push_back(adjoint ? 1u : 0u);
    }
    return ComputePipeline(context, info.name, stageSpirv(stage), sizeof(PushConstants), specialization);
}

}  // namespace

PathStages::PathStages(const VulkanContext& context, bool adjoint)
    : generate(stagePipeline(context, Stage::Generate, adjoint)),
      mediumSample(stagePipeline(context, Stage::MediumSample, adjoint)),
      shade(stagePipeline(context, Stage::Shade, adjoint)),
      shadow(stagePipeline(context, Stage::Shadow, adjoint)) {}

GradientPipelines::GradientPipelines(const VulkanContext& context)
    : adjoint(context, true), loss(stagePipeline(context, Stage::Loss)) {}

StagePipelines::StagePipelines(const VulkanContext& context)
    : primal(context, false),
      intersect(stagePipeline(context, Stage::Intersect)),
      queuePrepare(stagePipeline(context, Stage::QueuePrepare)),
      film(stagePipeline(context, Stage::Film)) {}

}  // namespace vkdr
