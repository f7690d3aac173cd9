// Next-event estimation in a scattering homogeneous medium has two strategies for the
// distance along a segment: distance sampling (the free flight's collision, whose next
// event shade.comp estimates) and equiangular sampling towards the light point
// (medium_sample.comp). Each samples the pair of a distance t and a light point y: the
// first t with the free flight's density p_free(t), then y as next-event estimation at
// x(t) does (p_nee(y), in solid angle where the emitter is large); the second y
// uniformly in area (p_area(y)), then t with the equiangular density p_equi(t | y).
// Each contribution is weighted by the power heuristic over the two pairs' densities,
// p_free p_nee against p_equi p_area (both light densities in solid angle at x(t)),
// which both stages compute from the same segment, t and y, so the weights sum to one.
// The phase-sampled path that reaches a light is weighted against light sampling as
// before; the light-sampled share of it is what the two distance strategies split.
#ifndef VKDR_DISTANCE_MIS_GLSL
#define VKDR_DISTANCE_MIS_GLSL
#include "constants.glsl"
#include "scene_access.glsl"
#include "sampling.glsl"
#include "medium.glsl"
#include "equiangular.glsl"
#include "lights.glsl"

// Whether a segment through medium m samples distances towards the light as well: in a
// homogeneous medium that scatters with an albedo of its own (no grids).
bool usesEquiangularSampling(GpuMedium m) {
    return kEquiangularSampling && m.densityGrid == kNoDensityGrid && m.albedoGrid == kNoDensityGrid &&
           maxComponent(m.sigma_s) > 0.0f;
}

// The segment from `origin` along `direction` to `tEnd`, as seen from a light sample
// `distance` away from the point at `t` in direction `wi` (distance kFar: a directional
// light, which equiangular sampling cannot aim at).
EquiangularSegment segmentTowardsLight(vec3 origin, vec3 direction, float tEnd, float t, vec3 wi, float distance) {
    vec3 lightPoint = origin + t * direction + distance * wi;
    EquiangularSegment s = equiangularSegment(origin, direction, tEnd, lightPoint);
    s.valid = s.valid && distance < kFar;
    return s;
}

// The density of a pair of a distance and a light point: 0 where either density is 0,
// even against an unbounded other (an emitter seen edge-on).
float pairPdf(float distancePdf, float lightPdf) {
    return distancePdf > 0.0f && lightPdf > 0.0f ? distancePdf * lightPdf : 0.0f;
}

// The power heuristic's weight of a pair sampled by one strategy against the other's
// density of the same pair.
float distanceStrategyWeight(float distancePdf, float lightPdf, float otherDistancePdf, float otherLightPdf) {
    return powerHeuristic(pairPdf(distancePdf, lightPdf), pairPdf(otherDistancePdf, otherLightPdf));
}

// The weight of the next event `light` from a collision at t that distance sampling
// found.
float freeFlightNextEventWeight(GpuMedium m, vec3 origin, vec3 direction, float tEnd, float t,
                                LightArrival light) {
    if (!usesEquiangularSampling(m)) {
        return 1.0f;
    }
    EquiangularSegment s = segmentTowardsLight(origin, direction, tEnd, t, light.wi, light.distance);
    return distanceStrategyWeight(freeFlightPdf(sigmaT(m), t), light.pdf, equiangularPdf(s, t), light.areaPdf);
}

#endif
