#version 460
#extension GL_GOOGLE_include_directive : require
// Adds each pixel's samples of this pass to the film, in sample order, so the sum is
// the same bit for bit whatever order the paths finished in. With a splitSample, the
// samples below it are also summed into filmBaseline.
#include "lib/stage_common.glsl"

void main() {
    uint p = gl_GlobalInvocationID.x;
    if (p >= pass.pixelCount) {
        return;
    }
    vec3 sum = vec3(0.0f);
    vec3 belowSplit = vec3(0.0f);
    for (uint s = 0u; s < pass.samplesInPass; ++s) {
        sum += P.radiance.v[s * pass.pixelCount + p].rgb;
        if (pass.firstSample + s + 1u == P.splitSample) {
            belowSplit = sum;
        }
    }
    P.film.v[pass.firstPixel + p].rgb += sum;
    if (P.splitSample > pass.firstSample) {
        P.filmBaseline.v[pass.firstPixel + p].rgb += pass.firstSample + pass.samplesInPass <= P.splitSample ? sum : belowSplit;
    }
}
