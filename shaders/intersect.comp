#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: the closest hit of each of this segment's rays, traced from where its segment
// starts, passing over the triangle it leaves (storeRay). The same in the primal and the
// adjoint pass.
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
    TraceHit hit = traceClosest(origin.xyz, direction, kFar, false, uvec2(floatBitsToUint(origin.w), kNoHit));
    P.hit.v[slot] = vec4(hit.t, hit.b1, hit.b2, uintBitsToFloat(hit.triangle));
}
