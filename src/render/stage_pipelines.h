#pragma once
#include "vk/pipeline.h"

namespace vkdr {

class VulkanContext;

// The stages that follow a path, compiled once as primal and once as adjoint
// (specialization constant 1 of shaders/lib/stage_common.glsl).
struct PathStages {
    PathStages(const VulkanContext& context, bool adjoint);

    ComputePipeline generate;
    ComputePipeline intersectShadow;
    ComputePipeline mediumSample;
    ComputePipeline shade;
};

// One pipeline per wavefront stage, named after its shader file.
struct StagePipelines {
    explicit StagePipelines(const VulkanContext& context);

    PathStages primal;
    PathStages adjoint;
    ComputePipeline intersect;  // closest hits: the same in both passes
    ComputePipeline film;
    ComputePipeline loss;
    ComputePipeline queuePrepare;
};

}  // namespace vkdr
