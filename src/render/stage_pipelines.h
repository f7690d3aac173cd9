#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "render/stages.h"
#include "vk/pipeline.h"

namespace vkdr {

class VulkanContext;

// What of the media the path stages are compiled to handle; a CPU device runs every
// branch of a shader, taken or not, so what a scene does not have is compiled out.
struct MediaFeatures {
    bool densityGrids = false;  // tracking through density grid media
    bool emission = false;      // gathering the emission of media (and its gradients)
    bool emissionGrids = false; // media whose emission follows an emission grid
    bool albedoGrids = false;   // media whose scattering an albedo grid colours
    bool anyMedium = false;     // free flight, emission and next events in media at all
    bool equiangularSampling = false;  // next events in scattering homogeneous media also sampled
                                       // towards the light (RenderSettings::equiangularSampling)

    bool operator==(const MediaFeatures&) const = default;
    // The features either has.
    MediaFeatures operator|(const MediaFeatures& other) const {
        return {.densityGrids = densityGrids || other.densityGrids,
                .emission = emission || other.emission,
                .emissionGrids = emissionGrids || other.emissionGrids,
                .albedoGrids = albedoGrids || other.albedoGrids,
                .anyMedium = anyMedium || other.anyMedium,
                .equiangularSampling = equiangularSampling || other.equiangularSampling};
    }
};

// The stages that follow a path (render/stages.h), compiled once as primal and once as
// adjoint pipelines; the adjoint ones add the gradients of `gradientKinds` (bit
// 1 << ParameterKind) alone.
struct PathStages {
    PathStages(const VulkanContext& context, bool adjoint, uint32_t gradientKinds, MediaFeatures media);

    // medium_sample and shade have a pipeline for each end of their queue (queues.glsl):
    // the back's (rays in vacuum, surface vertices) always, the front's (rays in a
    // medium, medium vertices) in a scene with media.
    ComputePipeline generate;
    ComputePipeline mediumSampleInVacuum;  // compiled without media
    std::optional<ComputePipeline> mediumSampleInMedia;
    ComputePipeline shadeSurfaces;
    std::optional<ComputePipeline> shadeMedia;
    ComputePipeline shadow;
};

// What only differentiation needs; compiled on first use, since a plain render
// should not pay for it, and again for other kinds of gradient or media features.
struct GradientPipelines {
    GradientPipelines(const VulkanContext& context, uint32_t gradientKinds, MediaFeatures media);

    uint32_t kinds;  // the kinds of parameter whose gradients the adjoint stages add
    MediaFeatures media;
    PathStages adjoint;
    ComputePipeline loss;
    ComputePipeline gradientValues;
};

// One pipeline per wavefront stage, named after it.
struct StagePipelines {
    StagePipelines(const VulkanContext& context, MediaFeatures media);

    PathStages primal;
    ComputePipeline intersect;  // closest hits: the same in both passes
    ComputePipeline queuePrepare;
    ComputePipeline film;
    std::unique_ptr<GradientPipelines> gradient;  // null until gradients are enabled
    // Gradient pipelines compiled before `gradient` for other kinds, most recent first,
    // so that a caller alternating between the parameters it differentiates compiles
    // each set once (Renderer::compileGradientPipelines).
    std::vector<std::unique_ptr<GradientPipelines>> earlierGradients;
};

}  // namespace vkdr
