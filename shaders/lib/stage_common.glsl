// Included first by every stage: extensions, the shared layouts and the push constants.
#ifndef VKDR_STAGE_COMMON_GLSL
#define VKDR_STAGE_COMMON_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_shader_subgroup_extended_types_int64 : require

#include "device_types.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer RenderParamsRef {
    RenderParams p;
};

layout(push_constant, std430) uniform Push {
    RenderParamsRef params;
    PassConstants pass;
};

layout(local_size_x = kWorkgroupSize) in;

// One source, two pipelines per stage: the primal pass renders, the adjoint pass
// replays the same paths and accumulates parameter gradients.
layout(constant_id = 0) const bool kAdjoint = false;
// The kinds of parameter whose gradients the adjoint pipelines add: bit (1 << kind),
// kGradientKind* in device_types.h. The other kinds' code is compiled out rather than
// skipped, since a CPU device runs every branch of a shader, taken or not.
layout(constant_id = 1) const uint kGradientKinds = 0xffffffffu;
// Whether the scene has density grid media: without them their tracking is compiled out,
// which a CPU device would otherwise pay for on every path.
layout(constant_id = 2) const bool kDensityGrids = true;
// Whether a medium of the scene emits (or, in the adjoint pipelines, the gradient of a
// medium's emission is wanted): without, gathering media's emission is compiled out.
layout(constant_id = 3) const bool kEmissiveMedia = true;
// Whether a medium of the scene has an emission grid, or an albedo grid: without, what
// reads them is compiled out.
layout(constant_id = 4) const bool kEmissionGrids = true;
layout(constant_id = 5) const bool kAlbedoGrids = true;
// Whether the scene has media at all: without, the medium stage only passes rays on.
layout(constant_id = 6) const bool kMedia = true;
// Whether next events in homogeneous media also sample distances towards the light
// (a homogeneous medium scatters, and equiangular sampling is not turned off).
layout(constant_id = 7) const bool kEquiangularSampling = true;
// The end of its queue that a stage with a pipeline for each end walks (kFrontEnd or
// kBackEnd, queues.glsl): medium_sample and shade.
layout(constant_id = 8) const uint kQueueEnd = 1u;

#define P params.p

#endif
