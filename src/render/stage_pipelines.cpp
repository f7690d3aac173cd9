#include "render/stage_pipelines.h"

#include <string>
#include <vector>

#include "render/push_constants.h"
#include "vkdr_shaders.h"

namespace vkdr {

namespace {

// Specialization constants: 0 selects shadow rays in intersect.comp, 1 the adjoint pass.
std::vector<uint32_t> variant(bool shadowRays, bool adjoint) {
    return {shadowRays ? 1u : 0u, adjoint ? 1u : 0u};
}

std::string stageName(const char* stage, bool adjoint) {
    return std::string(stage) + (adjoint ? " (adjoint)" : "");
}

}  // namespace

PathStages::PathStages(const VulkanContext& context, bool adjoint)
    : generate(context, stageName("generate", adjoint), spirv::generateSpirv(), sizeof(PushConstants),
               variant(false, adjoint)),
      intersectShadow(context, stageName("intersect (shadow)", adjoint), spirv::intersectSpirv(),
                      sizeof(PushConstants), variant(true, adjoint)),
      mediumSample(context, stageName("medium_sample", adjoint), spirv::mediumSampleSpirv(), sizeof(PushConstants),
                   variant(false, adjoint)),
      shade(context, stageName("shade", adjoint), spirv::shadeSpirv(), sizeof(PushConstants),
            variant(false, adjoint)) {}

GradientPipelines::GradientPipelines(const VulkanContext& context)
    : adjoint(context, true), loss(context, "loss", spirv::lossSpirv(), sizeof(PushConstants)) {}

StagePipelines::StagePipelines(const VulkanContext& context)
    : primal(context, false),
      intersect(context, "intersect", spirv::intersectSpirv(), sizeof(PushConstants), variant(false, false)),
      film(context, "film", spirv::filmSpirv(), sizeof(PushConstants)),
      queuePrepare(context, "queue_prepare", spirv::queuePrepareSpirv(), sizeof(PushConstants)) {}

}  // namespace vkdr
