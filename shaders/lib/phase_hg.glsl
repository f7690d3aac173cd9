// Henyey-Greenstein phase function. mu is the cosine between the incoming propagation
// direction and the outgoing direction, so g > 0 scatters forward. Every function here
// is finite and accurate to a few float roundings for g in the accepted range
// [-0.99, 0.99] and any mu: a cosine taken as the dot product of unit vectors may stray
// past +-1 by rounding, so mu is clamped first.
#ifndef VKDR_PHASE_HG_GLSL
#define VKDR_PHASE_HG_GLSL
#include "sampling.glsl"

// 1 + g^2 - 2 g mu as (1 - g mu)^2 + g^2 (1 - mu^2), a sum of non-negative terms: the
// direct form cancels to a few roundings (or below zero) at mu = +-1 when |g| is near 1.
float hgDenominator(float mu, float g) {
    float a = 1.0f - g * mu;
    return a * a + g * g * ((1.0f - mu) * (1.0f + mu));
}

float hgPhase(float mu, float g) {
    float denom = hgDenominator(clamp(mu, -1.0f, 1.0f), g);
    return kInv4Pi * ((1.0f - g) * (1.0f + g)) / (denom * sqrt(denom));
}

// d log p / d g, for the adjoint.
float hgPhaseDLogG(float mu, float g) {
    float m = clamp(mu, -1.0f, 1.0f);
    return -2.0f * g / ((1.0f - g) * (1.0f + g)) + 3.0f * (m - g) / hgDenominator(m, g);
}

// Inverts the CDF of mu exactly; the pdf of the result is hgPhase(mu, g). With
// e = 2u - 1 the inverse is mu = e + 2 g u (1 - u) (3 + 2 g e - g^2) / (1 + g e)^2: no
// division by g (the textbook (1 + g^2 - s^2) / (2 g) loses its digits as g -> 0, so
// needs an isotropic special case that is biased by O(g)), and mu = +-1 exactly at
// u = 0 and 1. 1 + g e and 3 + 2 g e - g^2 are written as sums of non-negative terms
// (w is the u on the side g leans to), which cancel nothing when |g| is near 1.
float sampleHgCosine(float u, float g) {
    float a = abs(g);
    float w = g >= 0.0f ? u : 1.0f - u;
    float t = (1.0f - a) + 2.0f * a * w;
    float c = (1.0f - a) * (3.0f + a) + 4.0f * a * w;
    float mu = (2.0f * u - 1.0f) + 2.0f * g * (u * (1.0f - u)) * c / (t * t);
    return clamp(mu, -1.0f, 1.0f);
}

vec3 sampleHg(vec3 incoming, float g, vec2 u) {
    return directionAround(incoming, sampleHgCosine(u.x, g), u.y);
}

#endif
