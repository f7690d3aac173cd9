// Next-event estimation from a point that equiangular sampling places along a segment
// through a scattering homogeneous medium, weighted against the next event from the free
// flight's own collision (distance_mis.glsl). Its shadow ray is traced here, in the
// medium stage, so that the replay has passed the contribution before the segment's
// free-flight factor, which does not multiply it, takes its gradient from L_rem.
#ifndef VKDR_EQUIANGULAR_NEXT_EVENT_GLSL
#define VKDR_EQUIANGULAR_NEXT_EVENT_GLSL
#include "lights.glsl"
#include "phase_hg.glsl"
#include "path_state.glsl"
#include "shadow_transmittance.glsl"
#include "distance_mis.glsl"

bool isDirectional(LightSample ls) {
    return ls.punctual != kNoPunctualLight && P.punctualLights.v[ls.punctual].type == kLightDirectional;
}

// The segment [0, tEnd) of the ray in `slot` through `medium`, entered with throughput
// beta, gathers C = beta sigma_s T(t) phase Le Tr w / (p_light p_t) from a light point
// (the light chosen as at a vertex, the point uniform in its area) and a distance t
// sampled towards it, Tr being the shadow ray's transmittance and w the product of the
// light-against-phase and the distance weights.
// The adjoint pass adds C's log-derivatives: -t for sigma_t, 1 / sigma_s (as C per unit
// sigma_s, so that a channel without scattering still has its gradient), the phase's in g,
// the emitter's, and the shadow ray's media.
void equiangularNextEvent(uint slot, uint medium, float tEnd, vec3 beta) {
    GpuMedium m = P.media.v[medium];
    PathInfo info = loadPathInfo(slot);
    if (!usesEquiangularSampling(m) || P.lightCount == 0u || info.depth == P.maxDepth) {
        return;
    }
    vec4 u = segmentRandom(info, kDimEquiangular);
    // The point on the light comes first, and sets the distance's density, so it is
    // sampled in area; its MIS weight is that of next-event estimation at the point lit.
    LightSample ls = sampleLightPoint(u.xyz);
    if (isDirectional(ls)) {
        return;
    }
    vec3 origin = P.rayOrigin.v[slot].xyz;
    vec3 direction = P.rayDirection.v[slot].xyz;
    EquiangularSegment segment = equiangularSegment(origin, direction, tEnd, ls.position);
    float t = sampleEquiangular(segment, u.w);
    float pdfT = equiangularPdf(segment, t);
    if (!(pdfT > 0.0f)) {
        return;
    }
    vec3 position = origin + t * direction;
    LightArrival light = lightArrival(ls, position);
    if (!(light.pdf > 0.0f)) {
        return;
    }
    if (!light.isDelta) {
        light.misPdf = nextEventPdf(ls.triangle, ls.pdfArea, position, ls.position, ls.normal);
    }
    float mu = dot(direction, light.wi);
    float phase = hgPhase(mu, m.g);
    vec3 sigma_t = sigmaT(m);
    float distanceWeight = distanceStrategyWeight(pdfT, light.pdf, freeFlightPdf(sigma_t, t), light.misPdf);
    float weight = lightSampleWeight(light, phase) * distanceWeight / pdfT;
    // Per unit of sigma_s and of the emitter's parameter.
    vec3 perUnit = beta * transmittance(sigma_t, t) * (phase * weight) * light.perUnit;
    vec3 unoccluded = perUnit * m.sigma_s * light.parameter;
    if (!(maxComponent(unoccluded) > 0.0f || (kAdjoint && maxComponent(perUnit) > 0.0f))) {
        return;
    }
    ShadowRay ray = shadowRay(light, position);
    vec3 tr = tracedShadowTransmittance(position, ray.direction, ray.distance, uvec2(kNoHit, ray.endTriangle),
                                        ray.leadOut, medium, unoccluded,
                                        segmentTrackingRandom(info, kTrackingEquiangularShadow),
                                        segmentTrackingRandom(info, kTrackingEquiangularShadowGradient));
    vec3 contribution = unoccluded * tr;
    gather(slot, contribution);
    if (kAdjoint) {
        vec3 normal = normalMask(adjoint);
        vec3 contributionWeight = delta * contribution * normal;
        addSigmaTGradient(medium, -t * contributionWeight);
        addSigmaSGradient(medium, delta * perUnit * light.parameter * tr * normal);
        addPhaseGGradient(medium, (contributionWeight.x + contributionWeight.y + contributionWeight.z) *
                                      hgPhaseDLogG(mu, m.g));
        addEmitterGradient(light.emitter, delta * perUnit * m.sigma_s * tr * normal);
    }
}

#endif
