// Next-event estimation in a scattering homogeneous medium has two strategies for the
// distance along a segment: distance sampling (the free flight's collision, whose next
// event shade.comp estimates) and equiangular sampling towards the light point
// (medium_sample.comp). For a distance t and a light point y, each contribution is
// weighted by the power heuristic over the two densities of t, which both stages compute
// from the same segment and y, so the weights sum to one. The phase-sampled path that
// reaches a light is weighted against light sampling as before; the light-sampled share
// of it is what the two distance strategies split.
#ifndef VKDR_DISTANCE_MIS_GLSL
#define VKDR_DISTANCE_MIS_GLSL
#include "constants.glsl"
#include "scene_access.glsl"
#include "sampling.glsl"
#include "medium.glsl"
#include "equiangular.glsl"

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

// The weight of the next event from a collision at t that distance sampling found.
float freeFlightNextEventWeight(GpuMedium m, vec3 origin, vec3 direction, float tEnd, float t, vec3 wi,
                                float distance) {
    if (!usesEquiangularSampling(m)) {
        return 1.0f;
    }
    EquiangularSegment s = segmentTowardsLight(origin, direction, tEnd, t, wi, distance);
    return powerHeuristic(freeFlightPdf(sigmaT(m), t), equiangularPdf(s, t));
}

#endif
