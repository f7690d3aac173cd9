// Homogeneous media: transmittance and free-flight sampling with spectral MIS over
// the RGB channels (docs/design.md, "Free flight with spectral MIS").
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

#endif
