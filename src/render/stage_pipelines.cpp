#include "render/stage_pipelines.h"

#include "render/push_constants.h"
#include "vkdr_shaders.h"

namespace vkdr {

StagePipelines::StagePipelines(const VulkanContext& context)
    : generate(context, "generate", spirv::generateSpirv(), sizeof(PushConstants)),
      intersect(context, "intersect", spirv::intersectSpirv(), sizeof(PushConstants), {0u}),
      intersectShadow(context, "intersect (shadow)", spirv::intersectSpirv(), sizeof(PushConstants), {1u}),
      mediumSample(context, "medium_sample", spirv::mediumSampleSpirv(), sizeof(PushConstants)),
      shade(context, "shade", spirv::shadeSpirv(), sizeof(PushConstants)),
      film(context, "film", spirv::filmSpirv(), sizeof(PushConstants)),
      queuePrepare(context, "queue_prepare", spirv::queuePrepareSpirv(), sizeof(PushConstants)) {}

}  // namespace vkdr
