// Henyey-Greenstein phase function. mu is the cosine between the incoming propagation
// direction and the outgoing direction, so g > 0 scatters forward.
#ifndef VKDR_PHASE_HG_GLSL
#define VKDR_PHASE_HG_GLSL
#include "sampling.glsl"

// Below this |g| the phase function is sampled as isotropic (the closed-form inverse
// divides by g); the density difference is O(g), below float resolution here.
const float kHgIsotropicBelow = 1.0e-3f;

float hgPhase(float mu, float g) {
    float denom = 1.0f + g * g - 2.0f * g * mu;
    return kInv4Pi * (1.0f - g * g) / (denom * sqrt(denom));
}

// d log p / d g, for the adjoint.
float hgPhaseDLogG(float mu, float g) {
    float denom = 1.0f + g * g - 2.0f * g * mu;
    return -2.0f * g / (1.0f - g * g) + 3.0f * (mu - g) / denom;
}

// Inverts the CDF of mu exactly; the pdf of the result is hgPhase(mu, g).
float sampleHgCosine(float u, float g) {
    if (abs(g) < kHgIsotropicBelow) {
        return 2.0f * u - 1.0f;
    }
    float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

vec3 sampleHg(vec3 incoming, float g, vec2 u) {
    return directionAround(incoming, sampleHgCosine(u.x, g), u.y);
}

#endif
