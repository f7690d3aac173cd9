#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 5: next-event shadow rays. A shadow ray passes through medium boundaries,
// multiplies the transmittance of every medium segment on its way to the light, and
// is blocked by the first opaque surface found; what gets through is gathered. The
// adjoint pass passes the same contribution and back-propagates its own factors:
// transmittance, scattering (albedo or phase) and emission.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/path_state.glsl"
#include "lib/shadow_transmittance.glsl"

// Random numbers for the shadow ray in `slot` (ratio tracking, or the adjoint's points),
// keyed by the segment that queued it (the w of its shadowContribution).
TrackingRandom shadowRandom(uint slot, uint segment, uint purpose) {
    PathInfo info = loadPathInfo(slot);
    info.segment = segment;
    return segmentTrackingRandom(info, purpose);
}

// The adjoint of a next-event contribution C = T * scatter * Le * w / pdf that reached
// the light with transmittance `tr` (whose gradients tracedShadowTransmittance added):
// the scattering and emission factors recorded by the shade stage.
void backpropagateNextEvent(uint slot, vec3 contribution, vec3 tr) {
    uvec4 vertex = P.shadowVertex.v[slot];
    vec3 normal = normalMask(adjoint);
    vec3 weight = delta * contribution * normal;
    vec4 scatterGradient = P.shadowScatterGradient.v[slot];
    vec4 emissionGradient = P.shadowEmissionGradient.v[slot];
    if (vertex.x == kVertexSurface) {
        addAlbedoGradient(vertex.y, P.surfaceHit.v[slot], delta * scatterGradient.rgb * tr * normal);
    } else {
        addPhaseGGradient(vertex.y, (weight.x + weight.y + weight.z) * scatterGradient.w);
    }
    addEmitterGradient(floatBitsToUint(emissionGradient.w), delta * emissionGradient.rgb * tr * normal);
}

void traceShadowRay() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(kQueueShadow)) {
        return;
    }
    uint slot = queueItem(kQueueShadow, index);
    vec4 startAndDistance = P.shadowOrigin.v[slot];
    vec4 direction = P.shadowDirection.v[slot];
    uint medium = floatBitsToUint(direction.w);
    // Read as one vec4: lavapipe (Mesa 22.3) compiled a read of its .rgb and one of its .w
    // before the trace into code whose tracking numbers followed the .rgb.
    vec4 contributionAndSegment = P.shadowContribution.v[slot];
    vec3 perUnitTransmittance = contributionAndSegment.rgb;
    uint segment = floatBitsToUint(contributionAndSegment.w);
    beginReplay(slot);
    holdMediumGradients(medium);
    if (kAdjoint) {
        // The derivative channels as they were at the vertex, before its continuation
        // (a channel never leaves derivative mode, nor changes the parameter it follows).
        // For this contribution only: the stage never stores the replay state back.
        uint atVertex = P.shadowVertex.v[slot].z;
        for (uint c = 0u; c < 3u; ++c) {
            if ((atVertex & (1u << c)) == 0u) {
                adjoint.targets[c] = kTargetNone;
            }
        }
    }
    vec4 ends = P.shadowEnds.v[slot];
    vec3 tr = tracedShadowTransmittance(startAndDistance.xyz, direction.xyz, startAndDistance.w,
                                        floatBitsToUint(ends.xy), ends.z, medium, perUnitTransmittance,
                                        shadowRandom(slot, segment, kTrackingShadow),
                                        shadowRandom(slot, segment, kTrackingShadowGradient));
    vec3 contribution = tr * perUnitTransmittance;
    gather(slot, contribution);
    if (kAdjoint) {
        backpropagateNextEvent(slot, contribution, tr);
    }
}

void main() {
    traceShadowRay();
    flushMediumGradients();
}
