// Homogeneous media: transmittance, free-flight sampling with spectral MIS over
// the RGB channels (docs/design.md, "Free flight with spectral MIS"), and what a
// segment gathers of a medium's emission.
#ifndef VKDR_MEDIUM_GLSL
#define VKDR_MEDIUM_GLSL
#include "constants.glsl"

vec3 transmittance(vec3 sigma_t, float t) {
    return exp(-sigma_t * t);
}

// sigma_s / sigma_t per channel: the weight of a collision sampled in proportion to
// sigma_t; 0 in a channel without extinction.
vec3 scatteringAlbedo(vec3 sigma_s, vec3 sigma_t) {
    return vec3(sigma_t.x > 0.0f ? sigma_s.x / sigma_t.x : 0.0f, sigma_t.y > 0.0f ? sigma_s.y / sigma_t.y : 0.0f,
                sigma_t.z > 0.0f ? sigma_s.z / sigma_t.z : 0.0f);
}

// Density of a sampled distance t: the channel-average of the per-channel exponentials,
// because the hero channel is picked uniformly.
float freeFlightPdf(vec3 sigma_t, float t) {
    return average(sigma_t * transmittance(sigma_t, t));
}

// Probability that the sampled distance lies beyond t.
float freeFlightSurvival(vec3 sigma_t, float t) {
    return average(transmittance(sigma_t, t));
}

// u.x picks the hero channel, u.y the distance in it; kFar when that channel is empty.
float sampleFreeFlight(vec3 sigma_t, vec2 u) {
    int channel = min(int(u.x * 3.0f), 2);
    float s = sigma_t[channel];
    return s > 0.0f ? -log(1.0f - u.y) / s : kFar;
}

// int_0^s exp(-sigma_t t) dt = (1 - exp(-sigma_t s)) / sigma_t per channel: what a
// segment of length s through a homogeneous medium gathers per unit of its emission
// (value), and the derivative of that with respect to sigma_t (dSigmaT). s may be kFar, a
// ray that leaves the scene. Near sigma_t s = 0, where 1 - exp(-sigma_t s) cancels, their
// series.
struct SegmentEmission {
    vec3 value;
    vec3 dSigmaT;
};

SegmentEmission emissionAlongSegment(vec3 sigma_t, float s) {
    SegmentEmission e;
    for (int c = 0; c < 3; ++c) {
        float x = sigma_t[c] * s;
        if (x < 0.25f) {
            // Six terms each: the first left out is below 5e-8 of the sum.
            e.value[c] = s * (1.0f - x * (1.0f / 2.0f - x * (1.0f / 6.0f - x * (1.0f / 24.0f - x * (1.0f / 120.0f -
                                                                                                   x / 720.0f)))));
            e.dSigmaT[c] = s * s * (-1.0f / 2.0f + x * (1.0f / 3.0f - x * (1.0f / 8.0f - x * (1.0f / 30.0f - x * (
                                                                                                   1.0f / 144.0f -
                                                                                                   x / 840.0f)))));
        } else {
            float t = exp(-x);
            e.value[c] = (1.0f - t) / sigma_t[c];
            e.dSigmaT[c] = (s * t - e.value[c]) / sigma_t[c];
        }
    }
    return e;
}

#endif
