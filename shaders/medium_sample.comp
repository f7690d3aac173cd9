#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 3: free-flight sampling in the medium the ray travels through. A distance
// before the surface hit becomes a medium vertex; otherwise the surface is the next
// vertex. Rays that leave the scene collect the background and end here.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/path_state.glsl"
#include "lib/scene_access.glsl"
#include "lib/medium.glsl"

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(pass.currentRays)) {
        return;
    }
    uint slot = queueItem(pass.currentRays, index);
    vec4 hit = P.hit.v[slot];
    bool escaped = floatBitsToUint(hit.w) == kNoHit;
    float tHit = escaped ? kFar : hit.x;
    uint medium = P.vertexInfo.v[slot].x;
    vec3 beta = P.beta.v[slot].rgb;
    uint vertexKind = kVertexSurface;
    if (medium != kNoMediumIndex) {
        GpuMedium m = P.media.v[medium];
        vec3 sigma_t = sigmaT(m);
        PathInfo info = loadPathInfo(slot);
        float t = sampleFreeFlight(sigma_t, segmentRandom(info, kDimFreeFlight).xy);
        if (t < tHit) {
            float pdf = freeFlightPdf(sigma_t, t);
            beta *= pdf > 0.0f ? m.sigma_s * transmittance(sigma_t, t) / pdf : vec3(0.0f);
            vertexKind = kVertexMedium;
            P.hit.v[slot].x = t;
        } else {
            float survival = freeFlightSurvival(sigma_t, tHit);
            beta *= survival > 0.0f ? transmittance(sigma_t, tHit) / survival : vec3(0.0f);
        }
    }
    if (vertexKind == kVertexSurface && escaped) {
        addRadiance(slot, beta * P.background.rgb);
        return;
    }
    if (maxComponent(beta) <= 0.0f) {
        return;
    }
    P.beta.v[slot].rgb = beta;
    P.vertexInfo.v[slot].y = vertexKind;
    queuePush(kQueueShade, slot);
}
