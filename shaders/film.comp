#version 460
#extension GL_GOOGLE_include_directive : require
// Adds each pixel's samples of this pass to the film one by one, in sample order, so the
// sum is the same bit for bit whatever order the paths finished in and however the
// samples were split into passes (every pass adds to the sum the passes before it left).
// With a splitSample, the samples below it are also added into filmBaseline, which thus
// holds the film's sum as it stood at the split.
#include "lib/stage_common.glsl"

void main() {
    uint p = gl_GlobalInvocationID.x;
    if (p >= pass.pixelCount) {
        return;
    }
    uint pixel = pass.firstPixel + p;
    vec3 film = P.film.v[pixel].rgb;
    bool below = pass.firstSample < P.splitSample;
    vec3 baseline = below ? P.filmBaseline.v[pixel].rgb : vec3(0.0f);
    for (uint s = 0u; s < pass.samplesInPass; ++s) {
        film += P.radiance.v[s * pass.pixelCount + p].rgb;
        if (pass.firstSample + s < P.splitSample) {
            baseline = film;
        }
    }
    P.film.v[pixel].rgb = film;
    if (below) {
        P.filmBaseline.v[pixel].rgb = baseline;
    }
}
