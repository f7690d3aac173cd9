#include "render/stage_pipelines.h"

#include <cassert>
#include <vector>

#include "device_types.h"
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
    case Stage::GradientValues: return spirv::gradientValuesSpirv();
    }
    return {};
}

namespace {

// The pipeline of a stage; of a stage with an adjoint variant, the primal or the adjoint one
// for the gradients of `gradientKinds`, for the media features `media` (specialization
// constants 0 to 7 of shaders/lib/stage_common.glsl), and for the end of its queue it
// walks (constant 8: medium_sample and shade). The dispatch timer's scope, not the name,
// tells the variants apart.
ComputePipeline stagePipeline(const VulkanContext& context, Stage stage, bool adjoint = false,
                              uint32_t gradientKinds = 0, MediaFeatures media = {},
                              uint32_t queueEnd = gpu::kBackEnd) {
    const StageInfo& info = stageInfo(stage);
    assert(info.hasAdjointVariant || !adjoint);
    std::vector<uint32_t> specialization;
    if (info.hasAdjointVariant) {
        specialization = {adjoint ? 1u : 0u,           gradientKinds,
                          media.densityGrids ? 1u : 0u,  media.emission ? 1u : 0u,
                          media.emissionGrids ? 1u : 0u, media.albedoGrids ? 1u : 0u,
                          media.anyMedium ? 1u : 0u,     media.equiangularSampling ? 1u : 0u,
                          queueEnd};
    }
    return ComputePipeline(context, info.name, stageSpirv(stage), sizeof(PushConstants), specialization);
}

}  // namespace

PathStages::PathStages(const VulkanContext& context, bool adjoint, uint32_t gradientKinds, MediaFeatures media)
    : generate(stagePipeline(context, Stage::Generate, adjoint, gradientKinds, media)),
      mediumSampleInVacuum(stagePipeline(context, Stage::MediumSample, adjoint, gradientKinds, MediaFeatures{})),
      shadeSurfaces(stagePipeline(context, Stage::Shade, adjoint, gradientKinds, media)),
      shadow(stagePipeline(context, Stage::Shadow, adjoint, gradientKinds, media)) {
    if (media.anyMedium) {
        mediumSampleInMedia.emplace(
            stagePipeline(context, Stage::MediumSample, adjoint, gradientKinds, media, gpu::kFrontEnd));
        shadeMedia.emplace(stagePipeline(context, Stage::Shade, adjoint, gradientKinds, media, gpu::kFrontEnd));
    }
}

GradientPipelines::GradientPipelines(const VulkanContext& context, uint32_t gradientKinds, MediaFeatures media)
    : kinds(gradientKinds), media(media), adjoint(context, true, gradientKinds, media),
      loss(stagePipeline(context, Stage::Loss)),
      gradientValues(stagePipeline(context, Stage::GradientValues)) {}

StagePipelines::StagePipelines(const VulkanContext& context, MediaFeatures media)
    : primal(context, false, 0, media),
      intersect(stagePipeline(context, Stage::Intersect)),
      queuePrepare(stagePipeline(context, Stage::QueuePrepare)),
      film(stagePipeline(context, Stage::Film)) {}

}  // namespace vkdr
