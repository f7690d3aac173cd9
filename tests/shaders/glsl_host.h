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
// Each test uses a few of the library's functions.
#pragma GCC diagnostic ignored "-Wunused-function"
using namespace glm;
using namespace gpu;
using uint = uint32_t;
#include "constants.glsl"
#include "rng.glsl"
#include "sampling.glsl"
#include "phase_hg.glsl"
#include "medium.glsl"
#include "fixed_point.glsl"
#pragma GCC diagnostic pop
}  // namespace
}  // namespace vkdr::glsl
