// The per-slot path state (structure of arrays, device_types.h) and the sample points
// of the path's current segment.
#ifndef VKDR_PATH_STATE_GLSL
#define VKDR_PATH_STATE_GLSL
#include "rng.glsl"
#include "tracking_random.glsl"

struct PathInfo {
    uint pixel;
    uint sampleIndex;
    uint depth;    // scattering vertices so far (surface bounces + medium scattering)
    uint segment;  // rays traced so far, pass-through boundaries included: keys the RNG
};

PathInfo loadPathInfo(uint slot) {
    uvec4 v = P.pathInfo.v[slot];
    return PathInfo(v.x, v.y, v.z, v.w);
}

void storePathInfo(uint slot, PathInfo info) {
    P.pathInfo.v[slot] = uvec4(info.pixel, info.sampleIndex, info.depth, info.segment);
}

// The stream a sample draws its numbers from (x) and its index in that stream (y).
uvec2 sampleStream(uint sampleIndex) {
    bool secondStream = P.secondStreamFrom > 0u && sampleIndex >= P.secondStreamFrom;
    return secondStream ? uvec2(P.firstStream + 1u, sampleIndex - P.secondStreamFrom)
                        : uvec2(P.firstStream, sampleIndex);
}

vec4 segmentRandom(PathInfo info, uint group) {
    uvec2 stream = sampleStream(info.sampleIndex);
    return sample4(info.pixel, stream.y, stream.x, info.segment * kDimGroupsPerSegment + group, P.seed);
}

TrackingRandom segmentTrackingRandom(PathInfo info, uint purpose) {
    uvec2 stream = sampleStream(info.sampleIndex);
    return trackingRandom(info.pixel, stream.y, stream.x, info.segment, purpose, P.seed);
}

// A ray from `start` that passes over the triangle it leaves (kNoHit: none; traceClosest).
void storeRay(uint slot, vec3 start, vec3 direction, uint leftTriangle) {
    P.rayOrigin.v[slot] = vec4(start, uintBitsToFloat(leftTriangle));
    P.rayDirection.v[slot] = vec4(direction, 0.0f);
}

#endif
