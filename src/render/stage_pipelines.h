#pragma once
#include <memory>

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

// What only differentiation needs; compiled on first use, since a plain render
// should not pay for it.
struct GradientPipelines {
    explicit GradientPipelines(const VulkanContext& context);

    PathStages adjoint;
    ComputePipeline loss;
};

// One pipeline per wavefront stage, named after its shader file.
struct StagePipelines {
    explicit StagePipelines(const VulkanContext& context);

    PathStages primal;
    ComputePipeline intersect;  // closest hits: the same in both passes
    ComputePipeline film;
    ComputePipeline queuePrepare;
    std::unique_ptr<GradientPipelines> gradient;  // null until gradients are enabled
};

}  // namespace vkdr
