#ifndef VKDR_TRACKING_RANDOM_GLSL
#define VKDR_TRACKING_RANDOM_GLSL
#include "constants.glsl"
#include "rng.glsl"

// Independent random numbers for loops that take as many as they need (tracking
// through density grids): a counter hashed with the key of its path segment (pixel,
// sample, stream, segment, purpose, seed), so replays draw the same ones.
const uint kTrackingFreeFlight = 0u;
const uint kTrackingShadow = 1u;
const uint kTrackingFreeFlightGradient = 2u;  // the adjoint's own points, independent of the tracking
const uint kTrackingShadowGradient = 3u;
const uint kTrackingEmission = 4u;            // a medium's emission along the segment (medium_emission.glsl)
const uint kTrackingEmissionGradient = 5u;
const uint kTrackingEquiangularShadow = 6u;   // the shadow ray of a segment's equiangular next event
const uint kTrackingEquiangularShadowGradient = 7u;
const uint kTrackingPurposes = 8u;
struct TrackingRandom {
    uvec4 key;
    uint counter;
};

TrackingRandom trackingRandom(uint pixel, uint sampleIndex, uint stream, uint segment, uint purpose, uint seed) {
    TrackingRandom r;
    r.key = pcg4d(uvec4(pixel, sampleIndex, (segment * 4u + stream) * kTrackingPurposes + purpose, seed));
    r.counter = 0u;
    return r;
}

vec4 nextTrackingRandom(INOUT(TrackingRandom) r) {
    ++r.counter;
    return toUnitFloat(pcg4d(r.key + uvec4(0u, 0u, 0u, r.counter)));
}

#endif
