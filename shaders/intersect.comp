#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: the closest hit of each of this segment's rays, traced from where the ray was
// spawned and measured from where its segment starts (storeRay). The same in the primal
// and the adjoint pass.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/bvh_traverse.glsl"

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(pass.currentRays)) {
        return;
    }
    uint slot = queueItem(pass.currentRays, index);
    vec4 origin = P.rayOrigin.v[slot];
    vec3 direction = P.rayDirection.v[slot].xyz;
    TraceHit hit = traceClosest(origin.xyz + origin.w * direction, direction, kFar, false);
    float t = hit.triangle == kNoHit ? hit.t : hit.t + origin.w;
    P.hit.v[slot] = vec4(t, hit.b1, hit.b2, uintBitsToFloat(hit.triangle));
}
