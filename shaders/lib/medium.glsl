// Homogeneous media: transmittance and free-flight sampling with spectral MIS over
// the RGB channels (docs/design.md, "Free flight with spectral MIS").
#ifndef VKDR_MEDIUM_GLSL
#define VKDR_MEDIUM_GLSL
#include "constants.glsl"

vec3 transmittance(vec3 sigma_t, float t) {
    return exp(-sigma_t * t);
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
