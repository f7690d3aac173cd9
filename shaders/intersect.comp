#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: the closest hit of each of this segment's rays. The same in the primal and
// the adjoint pass.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/bvh_traverse.glsl"

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(pass.currentRays)) {
        return;
    }
    uint slot = queueItem(pass.currentRays, index);
    TraceHit hit = traceClosest(P.rayOrigin.v[slot].xyz, P.rayDirection.v[slot].xyz, kFar, false);
    P.hit.v[slot] = vec4(hit.t, hit.b1, hit.b2, uintBitsToFloat(hit.triangle));
}
