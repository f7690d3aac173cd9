#version 460
#extension GL_GOOGLE_include_directive : require
// The loss of a rendered image against the target, per pixel, and the image adjoint
// dLoss/dI that seeds the adjoint pass. L2: mean of (I - T)^2; L1: mean of |I - T|.
// The image is the film (or the film less filmBaseline, see pass.lossImage) divided by
// the pass.samplesInPass samples it sums. dLoss/dI is divided by the full samples per
// pixel, so every path of the render carries its share whichever image it was taken at.
#include "lib/stage_common.glsl"
#include "lib/fixed_point_sums.glsl"

// The loss of one pixel's image value, and its dLoss/dI scaled for imageAdjoint.
float pixelLoss(uint p, vec3 image, out vec3 imageAdjoint) {
    vec3 difference = image - P.target.v[p].rgb;
    float loss;
    vec3 dLossDI;
    if (P.lossKind == kLossL1) {
        loss = dot(abs(difference), vec3(1.0f));
        dLossDI = sign(difference);
    } else {
        loss = dot(difference, difference);
        dLossDI = 2.0f * difference;
    }
    imageAdjoint = dLossDI * (P.lossScale * P.filmScale);
    return loss;
}

void main() {
    uint p = gl_GlobalInvocationID.x;
    if (p >= pass.pixelCount) {
        return;
    }
    vec3 film = P.film.v[p].rgb;
    vec3 imageAdjoint;
    float loss;
    if (pass.lossImage == kLossImageHalves) {
        // Paths at or above splitSample read the adjoint taken at the image below it,
        // and the paths below it the one taken at the image above (adjoint.glsl).
        vec3 below = P.filmBaseline.v[p].rgb;
        vec3 aboveAdjoint;
        pixelLoss(p, below / float(P.splitSample), imageAdjoint);
        pixelLoss(p, (film - below) / float(pass.samplesInPass - P.splitSample), aboveAdjoint);
        P.imageAdjoint.v[P.imagePixels + p] = vec4(aboveAdjoint, 0.0f);
        vec3 unused;
        loss = pixelLoss(p, film / float(pass.samplesInPass), unused);
    } else {
        if (pass.lossImage == kLossImageFilmMinusBaseline) {
            film -= P.filmBaseline.v[p].rgb;
        }
        loss = pixelLoss(p, film / float(pass.samplesInPass), imageAdjoint);
    }
    P.imageAdjoint.v[p] = vec4(imageAdjoint, 0.0f);
    addFixedPoint(P.lossSum, 0u, vec4(loss * P.lossScale, 0.0f, 0.0f, 0.0f), 1u);
}
