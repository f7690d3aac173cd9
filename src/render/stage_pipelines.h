#pragma once
#include <memory>

#include "render/stages.h"
#include "vk/pipeline.h"

namespace vkdr {

class VulkanContext;

// The stages that follow a path (render/stages.h), compiled once as primal and once as
// adjoint pipelines.
struct PathStages {
    PathStages(const VulkanContext& context, bool adjoint);

    ComputePipeline generate;
    ComputePipeline mediumSample;
    ComputePipeline shade;
    ComputePipeline shadow;
};

// What only differentiation needs; compiled on first use, since a plain render
// should not pay for it.
struct GradientPipelines {
    explicit GradientPipelines(const VulkanContext& context);

    PathStages adjoint;
    ComputePipeline loss;
};

// One pipeline per wavefront stage, named after it.
struct StagePipelines {
    explicit StagePipelines(const VulkanContext& context);

    PathStages primal;
    ComputePipeline intersect;  // closest hits: the same in both passes
    ComputePipeline queuePrepare;
    ComputePipeline film;
    std::unique_ptr<GradientPipelines> gradient;  // null until gradients are enabled
};

}  // namespace vkdr
