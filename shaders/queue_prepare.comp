#version 460
#extension GL_GOOGLE_include_directive : require
// Sizes the indirect dispatch that walks queue `queueArg` (for the shade queue, the two
// that walk each of its ends), and empties the queues in `clearMask` so the next stage
// can fill them. Counts the rays it sizes dispatches for.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"

DispatchArgs dispatchOver(uint count) {
    return DispatchArgs((count + kWorkgroupSize - 1u) / kWorkgroupSize, 1u, 1u, 0u);
}

void main() {
    if (gl_GlobalInvocationID.x != 0u) {
        return;
    }
    if (pass.queueArg == kQueueShade) {
        P.queueCounters.c.shadeEnds[kShadeMediumEnd] = dispatchOver(P.queueCounters.c.counts[kQueueShade]);
        P.queueCounters.c.shadeEnds[kShadeSurfaceEnd] = dispatchOver(P.queueCounters.c.shadeSurfaces);
    } else {
        uint count = queueSize(pass.queueArg);
        P.queueCounters.c.dispatch[pass.queueArg] = dispatchOver(count);
        P.queueCounters.c.raysTraced += count;
    }
    for (uint q = 0u; q < kQueueCount; ++q) {
        if ((pass.clearMask & (1u << q)) != 0u) {
            P.queueCounters.c.counts[q] = 0u;
        }
    }
    if ((pass.clearMask & (1u << kQueueShade)) != 0u) {
        P.queueCounters.c.shadeSurfaces = 0u;
    }
}
