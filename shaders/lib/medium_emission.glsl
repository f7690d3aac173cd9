// Emissive media (docs/design.md, "Emissive media"). A medium emits j(x) = emission d(x)
// per unit length, d the density (1 in a homogeneous medium; an emission grid's strength
// instead where it has one, gatherEmissionGrid), and attenuates with
// sigma_t d(x). A segment through it gathers, whatever the free flight that ends it
// samples, int_0^s T(t) j(t) dt, which is emission (1 - T(s)) / sigma_t exactly, since
// dT/dt = -sigma_t d(t) T(t) (emission D(s), D the density's integral, where sigma_t is
// 0): exact for a homogeneous medium, and in a density grid with ratio tracking's
// unbiased estimate of T(s) (and stratified points' of D). The adjoint pass adds the
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

// In a density grid, T(s) comes from ratio tracking along the segment and D from
// stratified points, each with numbers of its own; products of the two, which the
// adjoint needs, are unbiased because they are independent.
void gatherGridEmission(uint slot, uint medium, GpuMedium m, float tHit, vec3 beta) {
    GpuDensityGrid grid = P.densityGrids.v[m.densityGrid];
    PathInfo info = loadPathInfo(slot);
    vec3 origin = P.rayOrigin.v[slot].xyz;
    vec3 direction = P.rayDirection.v[slot].xyz;
    vec3 sigma_t = sigmaT(m);
    TrackingRandom random = segmentTrackingRandom(info, kTrackingEmission);
    float u = nextTrackingRandom(random).x;
    bool truncated = false;
    uint stepsLeft = kMaxTransmittanceSteps;
    vec3 transmittance = ratioTrackTransmittance(grid, origin, direction, tHit, sigma_t, random, stepsLeft, truncated);
    if (truncated) {
        atomicAdd(P.queueCounters.c.truncatedTracking, 1u);
    }
    bool anyUnattenuated = any(equal(sigma_t, vec3(0.0f)));
    float integral = anyUnattenuated ? densityIntegralAdjoint(grid, origin, direction, tHit, u, 0.0f) : 0.0f;
    vec3 perUnit;
    for (int c = 0; c < 3; ++c) {
        perUnit[c] = sigma_t[c] > 0.0f ? (1.0f - transmittance[c]) / sigma_t[c] : integral;
    }
    gather(slot, beta * m.emission * perUnit);
    if (!kAdjoint) {
        return;
    }
    vec3 g = contributionAdjoint(beta);
    addMediumEmissionGradient(medium, g * perUnit);
    // Where nothing is emitted the other gradients of the emission are 0, and without
    // sigma or density gradients nothing else is wanted.
    if (m.emission != vec3(0.0f) && gridGradientsWanted()) {
        // d/d sigma_t of emission (1 - T) / sigma_t is emission (D T / sigma_t - (1 - T) / sigma_t^2),
        // and -emission D^2 / 2 where sigma_t is 0; d/d D is emission T (emission where
        // sigma_t is 0), so the voxels get emission T dD/d(voxel).
        vec3 attenuation = mix(vec3(1.0f), transmittance, greaterThan(sigma_t, vec3(0.0f)));
        float voxelWeight = dot(g, m.emission * attenuation);
        TrackingRandom points = segmentTrackingRandom(info, kTrackingEmissionGradient);
        float d1 = densityIntegralAdjoint(grid, origin, direction, tHit, nextTrackingRandom(points).x, -voxelWeight);
        float d2 = anyUnattenuated ? densityIntegralAdjoint(grid, origin, direction, tHit,
                                                            nextTrackingRandom(points).x, 0.0f)
                                   : 0.0f;
        vec3 dSigmaT;
        for (int c = 0; c < 3; ++c) {
            dSigmaT[c] = sigma_t[c] > 0.0f ? (d1 * transmittance[c] - perUnit[c]) / sigma_t[c] : -0.5f * d1 * d2;
        }
        addSigmaTGradient(medium, g * m.emission * dSigmaT);
    }
}

const uint kEmissionGridPoints = kMaxTransmittancePoints;

// With an emission grid, j(t) = emission f(t), f the grid's strength, no longer follows
// the extinction, so the segment gathers int T(t) j(t) dt from stratified points t_k on
// its part [a, b) in the grid: emission (b - a) / N sum_k f(t_k) T(t_k), with T(t_k) exact
// in a homogeneous medium and ratio tracking's running estimate in a density grid, whose
// numbers are independent of the points', so every product is unbiased.
void gatherEmissionGrid(uint slot, uint medium, GpuMedium m, float tHit, vec3 beta) {
    GpuDensityGrid strength = P.densityGrids.v[m.emissionGrid];
    vec3 origin = P.rayOrigin.v[slot].xyz;
    vec3 direction = P.rayDirection.v[slot].xyz;
    GridRay ray = gridRay(strength, origin, direction);
    vec2 interval = cellsInterval(strength, ray, tHit);
    if (!(interval.x < interval.y)) {
        return;
    }
    PathInfo info = loadPathInfo(slot);
    TrackingRandom random = segmentTrackingRandom(info, kTrackingEmission);
    float u = nextTrackingRandom(random).x;
    float length = (interval.y - interval.x) / float(kEmissionGridPoints);
    TransmittancePoints points;
    points.count = kEmissionGridPoints;
    float f[kEmissionGridPoints];
    for (uint k = 0u; k < kEmissionGridPoints; ++k) {
        points.t[k] = interval.x + (float(k) + u) * length;
        f[k] = gridDensity(strength, ray.origin + points.t[k] * ray.direction);
    }
    vec3 sigma_t = sigmaT(m);
    bool inDensityGrid = m.densityGrid != kNoDensityGrid;
    if (inDensityGrid) {
        bool truncated = false;
        uint stepsLeft = kMaxTransmittanceSteps;
        ratioTrackTransmittanceAt(P.densityGrids.v[m.densityGrid], origin, direction,
                                  points.t[kEmissionGridPoints - 1u], sigma_t, random, stepsLeft, truncated, points);
        if (truncated) {
            atomicAdd(P.queueCounters.c.truncatedTracking, 1u);
        }
    } else {
        for (uint k = 0u; k < kEmissionGridPoints; ++k) {
            points.transmittance[k] = transmittance(sigma_t, points.t[k]);
        }
    }
    vec3 perUnit = vec3(0.0f);
    for (uint k = 0u; k < kEmissionGridPoints; ++k) {
        perUnit += (length * f[k]) * points.transmittance[k];
    }
    gather(slot, beta * m.emission * perUnit);
    if (!kAdjoint) {
        return;
    }
    vec3 g = contributionAdjoint(beta);
    addMediumEmissionGradient(medium, g * perUnit);
    // Where nothing is emitted the other gradients of the emission are 0.
    if (m.emission == vec3(0.0f)) {
        return;
    }
    if (gradientWanted(kGradientKindEmissionGrid)) {
        for (uint k = 0u; k < kEmissionGridPoints; ++k) {
            addTrilinearGradient(strength, ray.origin + points.t[k] * ray.direction,
                                 vec3(length * dot(g, m.emission * points.transmittance[k])), 1u);
        }
    }
    if (!gridGradientsWanted()) {
        return;
    }
    // d T_c(t) / d sigma_t,c = -D(t) T_c(t), D(t) the density's integral over [0, t) (t in
    // a homogeneous medium), estimated by points of its own; the voxels get
    // -sigma_t,c T_c(t) dD(t)/d(voxel).
    TrackingRandom gradientPoints = segmentTrackingRandom(info, kTrackingEmissionGradient);
    vec3 dSigmaT = vec3(0.0f);
    for (uint k = 0u; k < kEmissionGridPoints; ++k) {
        vec3 weight = g * m.emission * (length * f[k]) * points.transmittance[k];  // of T(t_k)
        float integral = points.t[k];
        if (inDensityGrid) {
            integral = densityIntegralAdjoint(P.densityGrids.v[m.densityGrid], origin, direction, points.t[k],
                                              nextTrackingRandom(gradientPoints).x, dot(weight, sigma_t));
        }
        dSigmaT -= weight * integral;
    }
    addSigmaTGradient(medium, dSigmaT);
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
