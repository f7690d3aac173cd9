// Counter-based random numbers: a pure function of (pixel, sample, segment, dimension
// group, seed), so the adjoint pass can replay a path in any scheduling order.
#ifndef VKDR_RNG_GLSL
#define VKDR_RNG_GLSL

// Dimension groups used within one path segment (four numbers each).
const uint kDimCamera = 0u;      // pixel jitter (segment 0 only)
const uint kDimFreeFlight = 1u;  // hero channel, distance
const uint kDimLight = 2u;       // emitter choice, point on the emitter
const uint kDimScatter = 3u;     // BSDF / phase direction, Russian roulette
const uint kDimGroupsPerSegment = 4u;

// pcg4d from Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020:
// a 4D-to-4D bijection with good avalanche, so neighbouring keys are independent.
uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// 24 high bits to a float in [0, 1): exact, and never 1.
vec4 toUnitFloat(uvec4 bits) {
    return vec4(bits >> 8u) * (1.0f / 16777216.0f);
}

vec4 uniform4(uint pixel, uint sampleIndex, uint segment, uint group, uint seed) {
    return toUnitFloat(pcg4d(uvec4(pixel, sampleIndex, segment * kDimGroupsPerSegment + group, seed)));
}

#endif
