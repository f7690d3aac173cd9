#ifndef VKDR_CONSTANTS_GLSL
#define VKDR_CONSTANTS_GLSL

const float kPi = 3.14159265358979f;
const float kInvPi = 0.318309886183791f;
const float kInv4Pi = 0.0795774715459477f;
// Stands in for an infinite distance; finite so that 0 * kFar stays 0.
const float kFar = 1.0e30f;

// A parameter a function writes back: GLSL's inout, and a reference where the tests
// compile this library as C++ (tests/shaders/glsl_host.h).
#ifndef INOUT
#define INOUT(Type) inout Type
#endif

float maxComponent(vec3 v) {
    return max(v.x, max(v.y, v.z));
}

float average(vec3 v) {
    return (v.x + v.y + v.z) * (1.0f / 3.0f);
}

#endif
