#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: closest hits of this segment's rays; as the shadow variant, next-event
// shadow rays, which pass through medium boundaries and multiply the transmittance of
// every medium segment on the way to the light.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/bvh_traverse.glsl"
#include "lib/medium.glsl"
#include "lib/adjoint.glsl"

layout(constant_id = 0) const bool kShadowRays = false;

// A shadow ray crossing more boundaries than this is treated as blocked.
const uint kMaxBoundaryCrossings = 64u;

void traceClosestHit(uint slot) {
    TraceHit hit = traceClosest(P.rayOrigin.v[slot].xyz, P.rayDirection.v[slot].xyz, kFar, false);
    P.hit.v[slot] = vec4(hit.t, hit.b1, hit.b2, uintBitsToFloat(hit.triangle));
}

// The media a shadow ray passes through and its length in each. The adjoint needs
// them once the transmittance is known: d C / d sigma_m = -length_m C for every medium
// m on the way. A ray through more distinct media than are kept is traced a second
// time to add its gradients.
const uint kRecordedMedia = 2u;
struct MediumLengths {
    uint medium[kRecordedMedia];
    float inMedium[kRecordedMedia];  // length of the ray in medium[i]
    uint count;
    bool complete;  // false: the ray passed through more media than were kept
};

MediumLengths noMediumLengths() {
    MediumLengths lengths;
    lengths.count = 0u;
    lengths.complete = true;
    return lengths;
}

void addMediumLength(inout MediumLengths lengths, uint medium, float length) {
    for (uint i = 0u; i < lengths.count; ++i) {
        if (lengths.medium[i] == medium) {
            lengths.inMedium[i] += length;
            return;
        }
    }
    if (lengths.count == kRecordedMedia) {
        lengths.complete = false;
        return;
    }
    lengths.medium[lengths.count] = medium;
    lengths.inMedium[lengths.count] = length;
    ++lengths.count;
}

// Transmittance from the shadow ray's origin to its end, zero when something opaque
// is in the way. In the adjoint pass it also records the length in each medium, and
// with `gradientWeight` != 0 adds gradientWeight * d log T / d sigma (minus each
// segment's length) to the sigma_a and sigma_s gradients of its medium.
vec3 shadowTransmittance(vec3 origin, vec3 direction, float distance, uint medium, vec3 gradientWeight,
                         inout MediumLengths lengths) {
    vec3 tr = vec3(1.0f);
    for (uint crossing = 0u; crossing <= kMaxBoundaryCrossings; ++crossing) {
        TraceHit hit = traceClosest(origin, direction, distance, true);
        if (hit.triangle != kNoHit && isOpaque(hit.triangle)) {
            return vec3(0.0f);
        }
        float segment = min(hit.t, distance);
        if (medium != kNoMediumIndex) {
            tr *= transmittance(sigmaT(P.media.v[medium]), segment);
            if (kAdjoint) {
                addMediumLength(lengths, medium, segment);
                if (maxComponent(abs(gradientWeight)) > 0.0f) {
                    addSigmaGradient(medium, -segment * gradientWeight, -segment * gradientWeight);
                }
            }
        }
        if (hit.triangle == kNoHit) {
            return tr;
        }
        SurfacePoint sp = surfacePoint(hit.triangle, hit.b1, hit.b2);
        GpuMaterial material = P.materials.v[sp.material];
        bool entering = dot(direction, sp.normal) < 0.0f;
        medium = entering ? uint(material.interiorMedium) : sp.outsideMedium;
        // Step past the boundary along the ray's side of it.
        vec3 next = sp.position + (entering ? -sp.normal : sp.normal) * P.rayEpsilon;
        distance -= dot(next - origin, direction);
        origin = next;
        if (distance <= 0.0f) {
            return tr;
        }
    }
    flagTruncatedLoop();
    return vec3(0.0f);
}

void traceShadowRay(uint slot) {
    vec4 origin = P.shadowOrigin.v[slot];
    vec4 direction = P.shadowDirection.v[slot];
    uint medium = floatBitsToUint(direction.w);
    MediumLengths lengths = noMediumLengths();
    vec3 tr = shadowTransmittance(origin.xyz, direction.xyz, origin.w, medium, vec3(0.0f), lengths);
    vec3 contribution = tr * P.shadowContribution.v[slot].rgb;
    if (!kAdjoint) {
        P.radiance.v[slot].rgb += contribution;
        return;
    }
    // The contribution's own factors: transmittance, scattering (albedo or phase), emission.
    uvec4 vertex = P.shadowVertex.v[slot];
    AdjointState s = loadAdjointState(slot);
    s.derivativeChannels = vertex.z;  // as it was at the vertex, before its continuation
    vec3 delta = pathAdjoint(slot);
    vec3 normal = normalMask(s);
    passContribution(slot, s, delta, contribution);
    vec3 weight = delta * contribution * normal;
    if (maxComponent(abs(weight)) > 0.0f) {
        if (lengths.complete) {
            for (uint i = 0u; i < lengths.count; ++i) {
                addSigmaGradient(lengths.medium[i], -lengths.inMedium[i] * weight, -lengths.inMedium[i] * weight);
            }
        } else {
            MediumLengths retraced = noMediumLengths();
            shadowTransmittance(origin.xyz, direction.xyz, origin.w, medium, weight, retraced);
        }
    }
    vec4 scatterGradient = P.shadowScatterGradient.v[slot];
    vec4 emissionGradient = P.shadowEmissionGradient.v[slot];
    if (vertex.x == kVertexSurface) {
        addAlbedoGradient(vertex.y, P.vertexUv.v[slot].xy, delta * scatterGradient.rgb * tr * normal);
    } else {
        addPhaseGGradient(vertex.y, (weight.x + weight.y + weight.z) * scatterGradient.w);
    }
    addEmissionGradient(floatBitsToUint(emissionGradient.w), delta * emissionGradient.rgb * tr * normal);
}

void main() {
    uint queue = kShadowRays ? kQueueShadow : pass.currentRays;
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(queue)) {
        return;
    }
    uint slot = queueItem(queue, index);
    if (kShadowRays) {
        traceShadowRay(slot);
    } else {
        traceClosestHit(slot);
    }
}
