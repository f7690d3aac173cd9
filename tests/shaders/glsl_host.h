#pragma once
// Compiles the pure-maths GLSL libraries of shaders/lib as C++ (with glm standing in
// for GLSL's types), so unit tests exercise the very code the stages run.
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "device_types.h"

namespace vkdr::glsl {
// Internal linkage: every test file gets its own copy of the non-inline GLSL functions.
namespace {
#pragma GCC diagnostic push
// Each test uses a few of the library's functions and variables.
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
using namespace glm;
using namespace gpu;
using uint = uint32_t;
#define INOUT(Type) Type&
// C++ neither fuses nor reassociates float operations here (no FMA in the x86-64
// baseline, no -ffast-math), which `precise` asks of a shader compiler.
#define precise
// What the grid library reads through the device's RenderParams (device_types.h): a
// test points these at its grid's voxels and majorant cells.
struct HostFloats {
    const float* v = nullptr;
};
struct HostRenderParams {
    HostFloats gridValues;
    HostFloats gridMajorants;
};
HostRenderParams P;
#include "constants.glsl"
#include "rng.glsl"
#include "sampling.glsl"
#include "phase_hg.glsl"
#include "medium.glsl"
#include "equiangular.glsl"
#include "spherical_triangle.glsl"
#include "fixed_point.glsl"
#include "compensated_sum.glsl"
#include "tracking_random.glsl"
#include "density_grid.glsl"
#include "grid_tracking.glsl"
#pragma GCC diagnostic pop
}  // namespace
}  // namespace vkdr::glsl
