#pragma once
#include "vk/pipeline.h"

namespace vkdr {

class VulkanContext;

// One pipeline per wavefront stage, named after its shader file.
struct StagePipelines {
    explicit StagePipelines(const VulkanContext& context);

    ComputePipeline generate;
    ComputePipeline intersect;
    ComputePipeline intersectShadow;
    ComputePipeline mediumSample;
    ComputePipeline shade;
    ComputePipeline film;
    ComputePipeline queuePrepare;
};

}  // namespace vkdr
