// Emissive media (docs/design.md, "Emissive media"). A medium emits j(x) = emission
// d(x) per unit length, d the density (1 in a homogeneous medium; an emission grid's
// strength instead where it has one, gatherEmissionGrid), and attenuates with sigma_t
// d(x). A segment through it gathers, whatever the free flight that ends it samples,
// int_0^s T(t) j(t) dt, which is emission (1 - T(s)) / sigma_t exactly, since dT/dt =
// -sigma_t d(t) T(t) (emission D(s), D the density's integral, where sigma_t is 0):
// exact for a homogeneous medium; in a density grid, a blend, channel by channel, of
// that closed form (with ratio tracking's unbiased estimate of T(s)) and an estimate
// from points along the segment (gatherGridEmission). The adjoint pass adds the
// gradients of this contribution to the medium's emission, sigma and voxels.
#ifndef VKDR_MEDIUM_EMISSION_GLSL
#define VKDR_MEDIUM_EMISSION_GLSL
#include "adjoint.glsl"
#include "grid_adjoint.glsl"
#include "medium.glsl"
#include "path_state.glsl"

bool mediumEmissionWanted(GpuMedium m) {
    return kEmissiveMedia &&
           (m.emission != vec3(0.0f) || (kAdjoint && gradientWanted(kGradientKindMediumEmission)));
}

// d log(contribution) is not defined where the contribution is 0, so the adjoint weights
// each derivative by delta * beta on the normal channels: the gradient of the loss with
// respect to the contribution.
vec3 contributionAdjoint(vec3 beta) {
    return delta * beta * normalMask(adjoint);
}

// A ray that leaves the scene through a homogeneous medium that does not attenuate in a
// channel would gather its emission without end: the loader refuses such emission, and
// the gradients leave that channel out (its derivative is infinite).
void gatherHomogeneousEmission(uint slot, uint medium, GpuMedium m, float tHit, vec3 beta) {
    vec3 sigma_t = sigmaT(m);
    SegmentEmission perUnit = emissionAlongSegment(sigma_t, tHit);
    gather(slot, beta * m.emission * perUnit.value);
    if (kAdjoint) {
        bvec3 finite = tHit < kFar ? bvec3(true) : greaterThan(sigma_t, vec3(0.0f));
        vec3 g = contributionAdjoint(beta);
        addMediumEmissionGradient(medium, mix(vec3(0.0f), g * perUnit.value, finite));
        // Where nothing is emitted the other gradients of the emission are 0.
        bvec3 emits = greaterThan(m.emission, vec3(0.0f));
        if (any(emits)) {
            vec3 dEmission = vec3(0.0f);
            for (int c = 0; c < 3; ++c) {
                dEmission[c] = emits[c] && finite[c] ? g[c] * m.emission[c] * perUnit.dSigmaT[c] : 0.0f;
            }
            addSigmaTGradient(medium, dEmission);
        }
    }
}

const uint kEmissionPoints = kMaxTransmittancePoints;

// A segment's emission from points along it (docs/design.md, "Emissive media"): where
// j(t) = emission f(t), f the trilinear value of `strength` (an emission grid, or the
// density grid itself), the part [a, b) of the segment inside strength's cells gets N
// stratified points t_k with one random offset, and int T(t) j(t) dt is estimated by
// emission (b - a) / N sum_k f(t_k) T(t_k).
struct EmissionPoints {
    GridRay ray;                 // the segment in strength's index coordinates
    TransmittancePoints points;  // the t_k (none where the segment misses the cells) and T(t_k)
    float strength[kEmissionPoints];
    float spacing;               // (b - a) / N, each point's share of the part
};

vec3 emissionPoint(EmissionPoints e, uint k) {
    return e.ray.origin + e.points.t[k] * e.ray.direction;
}

EmissionPoints placeEmissionPoints(GpuDensityGrid strength, vec3 origin, vec3 direction, float tHit, float u) {
    EmissionPoints e;
    e.ray = gridRay(strength, origin, direction);
    vec2 interval = cellsInterval(strength, e.ray, tHit);
    e.points.count = interval.x < interval.y ? kEmissionPoints : 0u;
    e.spacing = (interval.y - interval.x) / float(kEmissionPoints);
    for (uint k = 0u; k < e.points.count; ++k) {
        e.points.t[k] = interval.x + (float(k) + u) * e.spacing;
        e.strength[k] = gridDensity(strength, emissionPoint(e, k));
    }
    return e;
}

// The segment of the ray in `slot` over [0, tHit), its emission points placed on
// `strength`'s cells, and the streams its transmittance walk (random, after the points'
// offset) and its gradients' points (gradientRandom) draw from.
struct EmissionSegment {
    vec3 origin;
    vec3 direction;
    TrackingRandom random;
    TrackingRandom gradientRandom;
    EmissionPoints e;
};

EmissionSegment startEmissionSegment(uint slot, GpuDensityGrid strength, float tHit) {
    EmissionSegment s;
    s.origin = P.rayOrigin.v[slot].xyz;
    s.direction = P.rayDirection.v[slot].xyz;
    PathInfo info = loadPathInfo(slot);
    s.random = segmentTrackingRandom(info, kTrackingEmission);
    s.gradientRandom = segmentTrackingRandom(info, kTrackingEmissionGradient);
    s.e = placeEmissionPoints(strength, s.origin, s.direction, tHit, nextTrackingRandom(s.random).x);
    return s;
}

// Gives the points T(t_k): exact in a homogeneous medium, and in a density grid the
// running estimate of one ratio-tracking walk to tEnd (at least the last point), whose
// numbers follow the points' offset in `random`, so the two are independent. Returns the
// estimate of T(tEnd).
vec3 trackToEmissionPoints(GpuMedium m, vec3 origin, vec3 direction, float tEnd, vec3 sigma_t,
                           INOUT(TrackingRandom) random, INOUT(EmissionPoints) e) {
    if (!(kDensityGrids && m.densityGrid != kNoDensityGrid)) {
        for (uint k = 0u; k < e.points.count; ++k) {
            e.points.transmittance[k] = transmittance(sigma_t, e.points.t[k]);
        }
        return transmittance(sigma_t, tEnd);
    }
    bool truncated = false;
    uint stepsLeft = kMaxTransmittanceSteps;
    vec3 atEnd = ratioTrackTransmittanceAt(P.densityGrids.v[m.densityGrid], origin, direction, tEnd, sigma_t, random,
                                           stepsLeft, truncated, e.points);
    if (truncated) {
        atomicAdd(P.queueCounters.c.truncatedTracking, 1u);
    }
    return atEnd;
}

// (b - a) / N sum_k f(t_k) T(t_k), per unit emission.
vec3 emissionPointsSum(EmissionPoints e) {
    vec3 sum = vec3(0.0f);
    for (uint k = 0u; k < e.points.count; ++k) {
        sum += (e.spacing * e.strength[k]) * e.points.transmittance[k];
    }
    return sum;
}

// Adds the gradients of emissionPointsSum times `weight` per channel (the contribution's
// adjoint times the emission and the points' share of the estimate): to strength's voxels
// around each t_k, where gradients of `strengthKind` are wanted, and, since
// d T_c(t) / d sigma_t,c = -D(t) T_c(t) (D(t) the density's integral over [0, t), t in a
// homogeneous medium, estimated by stratified points from `gradientRandom`), to sigma_t
// and -sigma_t,c T_c(t_k) dD(t_k)/d(voxel) to the density's voxels.
void addEmissionPointsGradients(uint medium, GpuMedium m, vec3 origin, vec3 direction, vec3 sigma_t,
                                GpuDensityGrid strength, uint strengthKind, EmissionPoints e, vec3 weight,
                                INOUT(TrackingRandom) gradientRandom) {
    if (gradientWanted(strengthKind)) {
        for (uint k = 0u; k < e.points.count; ++k) {
            addTrilinearGradient(strength, emissionPoint(e, k), vec3(e.spacing * dot(weight, e.points.transmittance[k])),
                                 1u);
        }
    }
    if (!gridGradientsWanted()) {
        return;
    }
    bool inDensityGrid = kDensityGrids && m.densityGrid != kNoDensityGrid;
    vec3 dSigmaT = vec3(0.0f);
    for (uint k = 0u; k < e.points.count; ++k) {
        vec3 ofTransmittance = weight * (e.spacing * e.strength[k]) * e.points.transmittance[k];
        float integral = e.points.t[k];
        if (inDensityGrid) {
            integral = densityIntegralAdjoint(P.densityGrids.v[m.densityGrid], origin, direction, e.points.t[k],
                                              nextTrackingRandom(gradientRandom).x, dot(ofTransmittance, sigma_t));
        }
        dSigmaT -= ofTransmittance * integral;
    }
    addSigmaTGradient(medium, dSigmaT);
}

// Gathers emission mix(closedForm, the points' estimate, pointsShare) per channel and, in
// the adjoint, adds its gradients for the emission and the points' estimate's, the
// latter's points from `gradientRandom`. Returns the contribution's adjoint times the
// emission, with which a caller adds the closed form's other gradients; 0 where there are
// none (a forward pass, or a medium that emits nothing, whose other gradients are 0).
vec3 gatherEmissionBlend(uint slot, uint medium, GpuMedium m, vec3 origin, vec3 direction, vec3 beta, vec3 sigma_t,
                         GpuDensityGrid strength, uint strengthKind, EmissionPoints e, vec3 pointsShare,
                         vec3 closedForm, INOUT(TrackingRandom) gradientRandom) {
    vec3 perUnit = mix(closedForm, emissionPointsSum(e), pointsShare);
    gather(slot, beta * m.emission * perUnit);
    if (!kAdjoint) {
        return vec3(0.0f);
    }
    vec3 g = contributionAdjoint(beta);
    addMediumEmissionGradient(medium, g * perUnit);
    if (m.emission == vec3(0.0f)) {
        return vec3(0.0f);
    }
    addEmissionPointsGradients(medium, m, origin, direction, sigma_t, strength, strengthKind, e,
                               g * m.emission * pointsShare, gradientRandom);
    return g * m.emission;
}

// In a density grid j = emission d follows the extinction, so the segment also has the
// closed form emission (1 - T(s)) / sigma_t, with the walk's estimate of T(s) (docs/design.md,
// "Emissive media"). It is nearly exact where the segment is optically thick, but where
// it is thin the walk seldom samples a tentative collision and the closed form is 0 on
// most segments, while the points' estimate is smooth there. Each channel takes the
// points' estimate with weight exp(-sigma_t M), M the majorant's integral along the
// segment (sigma_t M the channel's majorant optical depth; the walk samples
// max(sigma_t) M tentative collisions on average), and the closed form with the rest. A
// channel that attenuates little thus takes the points' estimate, whose running
// transmittances stay near 1, even where another channel is thick. The weight is fixed
// by the scene and the ray, so the blend is unbiased; its gradient blends the two
// estimates' gradients alike (the weight's own derivative multiplies the difference of
// two unbiased estimates, 0 in expectation).
void gatherGridEmission(uint slot, uint medium, GpuMedium m, float tHit, vec3 beta) {
    GpuDensityGrid grid = P.densityGrids.v[m.densityGrid];
    EmissionSegment s = startEmissionSegment(slot, grid, tHit);
    if (s.e.points.count == 0u) {
        return;  // the segment misses the grid's cells, which hold all of its density
    }
    vec3 sigma_t = sigmaT(m);
    vec3 pointsShare = exp(-sigma_t * majorantIntegral(grid, s.e.ray, tHit));
    vec3 transmittance = trackToEmissionPoints(m, s.origin, s.direction, tHit, sigma_t, s.random, s.e);
    vec3 closedForm;
    for (int c = 0; c < 3; ++c) {
        closedForm[c] = sigma_t[c] > 0.0f ? (1.0f - transmittance[c]) / sigma_t[c] : 0.0f;
    }
    vec3 weight = gatherEmissionBlend(slot, medium, m, s.origin, s.direction, beta, sigma_t, grid,
                                      kGradientKindDensity, s.e, pointsShare, closedForm, s.gradientRandom);
    if (weight == vec3(0.0f) || !gridGradientsWanted()) {
        return;
    }
    // d/d sigma_t of (1 - T) / sigma_t is (D T - (1 - T) / sigma_t) / sigma_t, and d/dD is
    // T, so the voxels get T dD/d(voxel) from points of their own.
    vec3 closedFormWeight = weight * (vec3(1.0f) - pointsShare);
    float integral = densityIntegralAdjoint(grid, s.origin, s.direction, tHit, nextTrackingRandom(s.gradientRandom).x,
                                            -dot(closedFormWeight, transmittance));
    vec3 dSigmaT;
    for (int c = 0; c < 3; ++c) {
        dSigmaT[c] = sigma_t[c] > 0.0f
                         ? closedFormWeight[c] * (integral * transmittance[c] - closedForm[c]) / sigma_t[c]
                         : 0.0f;
    }
    addSigmaTGradient(medium, dSigmaT);
}

// With an emission grid, j(t) = emission f(t) no longer follows the extinction, and the
// points' estimate is the segment's whole gather (a blend with no closed form); their
// transmittance is wanted only up to the last point.
void gatherEmissionGrid(uint slot, uint medium, GpuMedium m, float tHit, vec3 beta) {
    GpuDensityGrid strength = P.densityGrids.v[m.emissionGrid];
    EmissionSegment s = startEmissionSegment(slot, strength, tHit);
    if (s.e.points.count == 0u) {
        return;
    }
    vec3 sigma_t = sigmaT(m);
    trackToEmissionPoints(m, s.origin, s.direction, s.e.points.t[kEmissionPoints - 1u], sigma_t, s.random, s.e);
    gatherEmissionBlend(slot, medium, m, s.origin, s.direction, beta, sigma_t, strength, kGradientKindEmissionGrid,
                        s.e, vec3(1.0f), vec3(0.0f), s.gradientRandom);
}

// Gathers the emission of `medium` along the segment [0, tHit) of the ray in `slot`
// (tHit is kFar for a ray that leaves the scene), beta being the throughput at its start.
void gatherMediumEmission(uint slot, uint medium, float tHit, vec3 beta) {
    GpuMedium m = P.media.v[medium];
    if (!mediumEmissionWanted(m)) {
        return;
    }
    if (kEmissionGrids && m.emissionGrid != kNoDensityGrid) {
        gatherEmissionGrid(slot, medium, m, tHit, beta);
    } else if (kDensityGrids && m.densityGrid != kNoDensityGrid) {
        gatherGridEmission(slot, medium, m, tHit, beta);
    } else {
        gatherHomogeneousEmission(slot, medium, m, tHit, beta);
    }
}

#endif
