#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 3: free-flight sampling in the medium the ray travels through, as the segment's
// end tells it (mediumAtSegmentEnd). The segment first gathers the medium's emission
// along it (medium_emission.glsl) and, in a scattering homogeneous medium, the next
// event from a point sampled towards a light (equiangular_next_event.glsl). A distance
// before the surface hit becomes a medium vertex; otherwise the surface is the next
// vertex. Rays that leave the scene collect the background and end here. The adjoint
// pass adds delta * L_rem * d log(segment weight) to the medium's sigma gradients.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/path_state.glsl"
#include "lib/scene_access.glsl"
#include "lib/medium.glsl"
#include "lib/adjoint.glsl"
#include "lib/grid_adjoint.glsl"
#include "lib/medium_emission.glsl"
#include "lib/equiangular_next_event.glsl"

// Whether a ray through the medium can go straight to the surface, weighted by its
// transmittance: nothing scatters, and no path needs a collision to find the gradient of
// sigma_s at 0 (derivative mode). Sampling a collision there would only end the path.
bool passesThroughAbsorbing(GpuMedium m) {
    return m.sigma_s == vec3(0.0f) && P.sampleNonScatteringMedia == 0u;
}

// A collision in a medium with an albedo grid scatters a(x) of what it would otherwise,
// and absorbs the rest: the extinction, and with it the free flight, are unchanged. The
// adjoint pass adds delta * L_rem * w_v / a_c(x) to channel c of each voxel v that x
// blends (w_v its trilinear weight); where a_c(x) is 0 the primal path ends in that
// channel, and the adjoint goes on in derivative mode for the voxels around x
// (docs/density-grids.md, "Albedo grids").
void scatterByAlbedoGrid(uint slot, GpuMedium m, vec3 position, inout vec3 beta) {
    if (!kAlbedoGrids || m.albedoGrid == kNoDensityGrid) {
        return;
    }
    GpuDensityGrid grid = P.densityGrids.v[m.albedoGrid];
    vec3 index = gridRay(grid, position, vec3(0.0f)).origin;
    vec3 albedo = gridAlbedo(grid, index);
    vec3 after = beta * albedo;
    if (kAdjoint) {
        if (gradientWanted(kGradientKindAlbedoGrid)) {
            addTrilinearGradient(grid, index, factorGradient(slot, logDerivativeOfLinear(albedo)), 3u);
        }
        bvec3 entered;
        after = enterDerivativeMode(after, albedo, beta, kTargetAlbedoPoint, m.albedoGrid, entered);
        for (uint c = 0u; c < 3u; ++c) {
            if (entered[c]) {
                P.albedoTargetPoints.v[slot * 3u + c] = vec4(index, 0.0f);
            }
        }
    }
    beta = after;
}

// A real collision in a grid weighs density / chance (trackFreeFlight's defensive
// acceptance; 1 otherwise). Where the density is 0 the primal path ends there, and the
// adjoint pass goes on in derivative mode for the voxels around the point: the
// derivative of the collision's factor with respect to the density there is 1 / chance.
vec3 weighGridCollision(uint slot, uint gridIndex, GridFreeFlight flight, vec3 beta) {
    if (flight.density == flight.chance) {
        return beta;
    }
    vec3 after = beta * (flight.density / flight.chance);
    if (kAdjoint && flight.density == 0.0f) {
        bvec3 entered;
        after = enterDerivativeMode(after, vec3(0.0f), beta / flight.chance, kTargetDensityPoint, gridIndex, entered);
        if (any(entered)) {
            P.densityTargetPoint.v[slot] = vec4(flight.index, 0.0f);
        }
    }
    return after;
}

// Free flight through a density grid medium along [0, tHit) (grid_tracking.glsl): the
// medium vertex of a real collision, a pause where tracking reached its step bound, or
// the surface. A medium that scatters nowhere is passed with its ratio-tracked
// transmittance. The adjoint pass adds delta * L_rem * d log(segment factor) to the
// medium's sigma gradients, also for a ray that leaves the scene (the grid ends).
uint sampleGridFreeFlightVertex(uint slot, uint medium, GpuMedium m, float tHit, inout vec3 beta) {
    GpuDensityGrid grid = P.densityGrids.v[m.densityGrid];
    PathInfo info = loadPathInfo(slot);
    TrackingRandom random = segmentTrackingRandom(info, kTrackingFreeFlight);
    vec3 origin = P.rayOrigin.v[slot].xyz;
    vec3 direction = P.rayDirection.v[slot].xyz;
    vec3 sigma_t = sigmaT(m);
    GridFreeFlight flight;
    flight.t = tHit;
    flight.collided = false;
    flight.paused = false;
    if (m.sigma_s == vec3(0.0f)) {
        bool truncated = false;
        uint stepsLeft = kMaxTransmittanceSteps;
        beta *= ratioTrackTransmittance(grid, origin, direction, tHit, sigma_t, random, stepsLeft, truncated);
        if (truncated) {
            atomicAdd(P.queueCounters.c.truncatedTracking, 1u);
        }
    } else {
        vec4 u = segmentRandom(info, kDimFreeFlight);
        int hero = min(int(u.x * 3.0f), 2);
        float defensiveDensity = P.defensiveGridCollisions != 0u
                                     ? kDefensiveCollisionsPerCrossing * grid.tracking.x / maxComponent(sigma_t)
                                     : 0.0f;
        flight = trackFreeFlight(grid, origin, direction, tHit, sigma_t[hero], u.yz, defensiveDensity, random);
        beta *= heroMisWeight(sigma_t, flight.tentative, flight.majorantIntegral) * flight.nullWeight;
        if (flight.collided) {
            beta *= scatteringAlbedo(m.sigma_s, sigma_t);
            beta = weighGridCollision(slot, m.densityGrid, flight, beta);
            scatterByAlbedoGrid(slot, m, origin + flight.t * direction, beta);
        }
    }
    if (kAdjoint && gridGradientsWanted()) {
        // The segment's factor is T(t), times sigma_s d(x_t) at a collision
        // (grid_adjoint.glsl).
        vec3 weight = factorGradient(slot, vec3(1.0f));
        TrackingRandom points = segmentTrackingRandom(info, kTrackingFreeFlightGradient);
        float integral = densityIntegralAdjoint(grid, origin, direction, flight.t, nextTrackingRandom(points).x,
                                                dot(weight, sigma_t));
        vec3 dLogScattering = flight.collided ? logDerivativeOfLinear(m.sigma_s) : vec3(0.0f);
        addSigmaTGradient(medium, -integral * weight);
        addSigmaSGradient(medium, dLogScattering * weight);
        if (flight.collided && flight.density > 0.0f) {
            addTrilinearDensityGradient(grid, flight.index, (weight.x + weight.y + weight.z) / flight.density);
        }
    }
    if (!(flight.collided || flight.paused)) {
        return kVertexSurface;
    }
    P.hit.v[slot].xy = vec2(flight.t, tHit);
    return flight.collided ? kVertexMedium : kVertexPause;
}

// Samples a free-flight distance in `medium` along the segment and multiplies beta by
// its weight; returns the kind of the segment's vertex. The adjoint pass adds
// delta * L_rem * d log(weight) to the medium's sigma gradients.
uint sampleFreeFlightVertex(uint slot, uint medium, float tHit, bool escaped, inout vec3 beta) {
    GpuMedium m = P.media.v[medium];
    if (kDensityGrids && m.densityGrid != kNoDensityGrid) {
        return sampleGridFreeFlightVertex(slot, medium, m, tHit, beta);
    }
    vec3 sigma_t = sigmaT(m);
    bool absorbing = passesThroughAbsorbing(m);
    float t = absorbing ? kFar : sampleFreeFlight(sigma_t, segmentRandom(loadPathInfo(slot), kDimFreeFlight).xy);
    if (t < tHit) {
        // Medium vertex: weight sigma_s T(t) / p(t), with the pdf p held fixed.
        float pdf = freeFlightPdf(sigma_t, t);
        vec3 perUnitScattering = pdf > 0.0f ? transmittance(sigma_t, t) / pdf : vec3(0.0f);
        if (kAdjoint) {
            addSigmaTGradient(medium, factorGradient(slot, vec3(-t)));
            addSigmaSGradient(medium, factorGradient(slot, logDerivativeOfLinear(m.sigma_s)));
        }
        beta = multiplyByParameter(beta, m.sigma_s, perUnitScattering, kTargetMediumScattering, medium);
        scatterByAlbedoGrid(slot, m, P.rayOrigin.v[slot].xyz + t * P.rayDirection.v[slot].xyz, beta);
        // The segment's end too: the vertex's next event weighs itself against
        // equiangular sampling over the same segment (distance_mis.glsl).
        P.hit.v[slot].xy = vec2(t, tHit);
        return kVertexMedium;
    }
    // Surface vertex (or escape): weight T(t_hit) / P(t > t_hit), where P is 1 when
    // nothing was sampled.
    float survival = absorbing ? 1.0f : freeFlightSurvival(sigma_t, tHit);
    beta *= survival > 0.0f ? transmittance(sigma_t, tHit) / survival : vec3(0.0f);
    // An escaped ray's L_rem is zero wherever T(infinity) is; where sigma_t = 0 the
    // derivative is undefined and left out.
    if (kAdjoint && !escaped) {
        addSigmaTGradient(medium, factorGradient(slot, vec3(-tHit)));
    }
    return kVertexSurface;
}

void sampleSegment() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= endSize(pass.currentRays)) {
        return;
    }
    uint slot = endItem(pass.currentRays, index);
    vec4 hit = P.hit.v[slot];
    bool escaped = floatBitsToUint(hit.w) == kNoHit;
    float tHit = escaped ? kFar : hit.x;
    uvec2 vertex = P.vertexInfo.v[slot].xy;  // the medium, and the kind of the vertex the ray left
    uint medium = vertex.x;
    if (kMedia) {
        medium = mediumAtSegmentEnd(floatBitsToUint(hit.w), P.rayDirection.v[slot].xyz, medium);
        if (medium != vertex.x) {
            P.vertexInfo.v[slot].x = medium;
        }
    }
    vec3 beta = P.beta.v[slot].rgb;
    beginReplay(slot);
    holdMediumGradients(medium);
    applyPendingFactor(slot);
    uint vertexKind = kVertexSurface;
    if (kMedia && medium != kNoMediumIndex) {
        // A segment that goes on from a pause has had its emission gathered, up to the
        // same surface, by the segment that paused.
        if (vertex.y != kVertexPause) {
            gatherMediumEmission(slot, medium, tHit, beta);
            equiangularNextEvent(slot, medium, tHit, beta);
        }
        vertexKind = sampleFreeFlightVertex(slot, medium, tHit, escaped, beta);
    }
    if (vertexKind == kVertexSurface && escaped) {
        gather(slot, beta * P.background.rgb);
        return;
    }
    if (maxComponent(beta) <= 0.0f) {
        return;
    }
    endReplay(slot);
    P.beta.v[slot].rgb = beta;
    P.vertexInfo.v[slot].y = vertexKind;
    queueShade(slot, vertexKind == kVertexSurface);
}

void main() {
    sampleSegment();
    flushMediumGradients();
}
