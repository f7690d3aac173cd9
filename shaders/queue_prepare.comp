#version 460
#extension GL_GOOGLE_include_directive : require
// Sizes the indirect dispatches that walk queue `queueArg` whole and each of its ends,
// and empties the queues in `clearMask` so the next stage can fill them. Counts the
// rays it sizes dispatches for.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"

DispatchArgs dispatchOver(uint count) {
    return DispatchArgs((count + kWorkgroupSize - 1u) / kWorkgroupSize, 1u, 1u, 0u);
}

void main() {
    if (gl_GlobalInvocationID.x != 0u) {
        return;
    }
    uint count = queueSize(pass.queueArg);
    P.queueCounters.c.dispatch[pass.queueArg] = dispatchOver(count);
    P.queueCounters.c.ends[kFrontEnd] = dispatchOver(P.queueCounters.c.counts[pass.queueArg]);
    P.queueCounters.c.ends[kBackEnd] = dispatchOver(P.queueCounters.c.backCounts[pass.queueArg]);
    if (pass.queueArg != kQueueShade) {
        P.queueCounters.c.raysTraced += count;
    }
    for (uint q = 0u; q < kQueueCount; ++q) {
        if ((pass.clearMask & (1u << q)) != 0u) {
            P.queueCounters.c.counts[q] = 0u;
            P.queueCounters.c.backCounts[q] = 0u;
        }
    }
}
