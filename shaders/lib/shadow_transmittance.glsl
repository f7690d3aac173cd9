// The transmittance of a shadow ray through the media on its way (homogeneous media and
// density grids, across medium boundaries), and its adjoint: shared by the shadow stage
// and by next-event estimation from points sampled along a segment (medium_sample).
#ifndef VKDR_SHADOW_TRANSMITTANCE_GLSL
#define VKDR_SHADOW_TRANSMITTANCE_GLSL
#include "bvh_traverse.glsl"
#include "medium.glsl"
#include "adjoint.glsl"
#include "grid_adjoint.glsl"

// A shadow ray crossing more boundaries than this is treated as blocked.
const uint kMaxBoundaryCrossings = 64u;

// The media a shadow ray passes through and its length in each. The adjoint needs
// them once the transmittance is known: d C / d sigma_m = -length_m C for every medium
// m on the way. Where a grid's voxel gradients are wanted, it keeps the segments through
// grids instead, whose points (densityIntegralAdjoint) need the contribution's weight. A
// ray through more distinct media or grid segments than are kept is traced a second time
// to add its gradients (tracedShadowTransmittance).
const uint kRecordedMedia = 2u;
const uint kRecordedGridSegments = 2u;
struct MediumLengths {
    uint medium[kRecordedMedia];
    float inMedium[kRecordedMedia];  // length of the ray in medium[i]
    uint count;
    uint gridMedium[kRecordedGridSegments];
    vec4 gridSegment[kRecordedGridSegments];  // xyz: where the segment starts; w: its length
    vec3 gridDirection[kRecordedGridSegments];
    uint gridSegments;
    bool complete;  // false: through more media or grid segments than were kept
};

MediumLengths noMediumLengths() {
    MediumLengths lengths;
    lengths.count = 0u;
    lengths.gridSegments = 0u;
    lengths.complete = true;
    return lengths;
}

void addGridSegment(inout MediumLengths lengths, uint medium, vec3 origin, vec3 direction, float length) {
    if (lengths.gridSegments == kRecordedGridSegments) {
        lengths.complete = false;
        return;
    }
    lengths.gridMedium[lengths.gridSegments] = medium;
    lengths.gridSegment[lengths.gridSegments] = vec4(origin, length);
    lengths.gridDirection[lengths.gridSegments] = direction;
    ++lengths.gridSegments;
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

// The density's integral along a grid medium's segment, estimated at the next of the
// shadow ray's own points; adds -voxelWeight . sigma_t times its voxel derivatives
// (densityIntegralAdjoint). The first trace and addRecordedTransmittanceGradients draw the
// points of a ray's grid segments in the same order.
float gridSegmentOpticalLength(GpuMedium m, vec3 origin, vec3 direction, float length, vec3 voxelWeight,
                               inout TrackingRandom gradientPoints) {
    return densityIntegralAdjoint(P.densityGrids.v[m.densityGrid], origin, direction, length,
                                  nextTrackingRandom(gradientPoints).x, dot(voxelWeight, sigmaT(m)));
}

// Transmittance from the shadow ray's start to the light `distance` along it, zero when
// something opaque is in the way. The ray passes over the triangles in `skipped`, the
// one it leaves and the emitter triangle it ends on (traceClosest), and over each
// boundary it crosses as it leaves it; it is traced to `leadOut` before the light
// (LightArrival.leadOut), a stretch that counts in the medium there. In the adjoint pass
// it also records the length in each medium, and with `gradientWeight` != 0 adds
// gradientWeight * d log T / d sigma_t (minus each segment's length, or in a density grid
// the density's integral along it, estimated at points of its own) to its medium's
// sigma_t gradient. A ray to a directional light (distance kFar) ends in an unbounded
// segment, whose transmittance is 0 wherever sigma_t > 0; where sigma_t = 0 its
// derivative is unbounded and left out, as for a camera ray that escapes.
vec3 shadowTransmittance(vec3 start, vec3 direction, float distance, uvec2 skipped, float leadOut, uint medium,
                         vec3 gradientWeight, inout MediumLengths lengths, inout TrackingRandom random,
                         inout TrackingRandom gradientPoints) {
    vec3 tr = vec3(1.0f);
    bool toInfinity = distance >= kFar;
    vec3 end = start + direction * distance;
    // A trace for the gradients alone (a weight is given) needs no transmittance.
    bool forGradientsOnly = maxComponent(abs(gradientWeight)) > 0.0f;
    uint trackingStepsLeft = kMaxTransmittanceSteps;
    bool truncated = false;
    for (uint crossing = 0u; crossing <= kMaxBoundaryCrossings; ++crossing) {
        TraceHit hit = traceClosest(start, direction, toInfinity ? kFar : distance - leadOut, true, skipped);
        if (hit.triangle != kNoHit && isOpaque(hit.triangle)) {
            return vec3(0.0f);
        }
        // The segment in the medium: from its start to the hit, or to the light. One that
        // ends on a boundary is in the medium its far end tells (as mediumAtSegmentEnd,
        // from the boundary's surface point, where the ray goes on); one that ends at a
        // light is in the medium the ray carries.
        float segment = hit.triangle == kNoHit ? distance : hit.t;
        SurfacePoint sp;
        float facing = 0.0f;
        int interior = -1;
        if (hit.triangle != kNoHit) {
            sp = surfacePoint(hit.triangle, hit.b1, hit.b2);
            facing = dot(direction, sp.normal);
            interior = P.materials.v[sp.material].interiorMedium;
            if (kMedia) {
                medium = mediumBeforeBoundary(uint(interior), sp.outsideMedium, facing, medium);
            }
        } else if (kMedia && toInfinity) {
            medium = mediumAtSegmentEnd(kNoHit, direction, medium);
        }
        if (kMedia && medium != kNoMediumIndex) {
            GpuMedium m = P.media.v[medium];
            // d log T / d sigma_t = -(the optical length per unit sigma_t): the segment's
            // length, or in a grid the density's integral along it.
            float opticalLength = segment;
            bool unbounded = toInfinity && hit.triangle == kNoHit;
            bool awaitsWeight = false;  // a grid segment whose gradients addRecordedTransmittanceGradients adds
            if (kDensityGrids && m.densityGrid != kNoDensityGrid) {
                GpuDensityGrid grid = P.densityGrids.v[m.densityGrid];
                if (!forGradientsOnly) {
                    tr *= ratioTrackTransmittance(grid, start, direction, segment, sigmaT(m), random,
                                                  trackingStepsLeft, truncated);
                }
                if (truncated) {
                    atomicAdd(P.queueCounters.c.truncatedTracking, 1u);
                    return vec3(0.0f);
                }
                unbounded = false;  // the grid ends
                if (kAdjoint && gridGradientsWanted()) {
                    if (gradientWanted(kGradientKindDensity) && !forGradientsOnly) {
                        // Voxel gradients need the contribution's weight, known once the
                        // whole ray is: addRecordedTransmittanceGradients estimates the
                        // density's integral along the segment then, with the weight.
                        addGridSegment(lengths, medium, start, direction, segment);
                        awaitsWeight = true;
                    } else {
                        opticalLength =
                            gridSegmentOpticalLength(m, start, direction, segment, gradientWeight, gradientPoints);
                    }
                }
            } else {
                tr *= transmittance(sigmaT(m), segment);
            }
            if (kAdjoint && !unbounded && !awaitsWeight) {
                addMediumLength(lengths, medium, opticalLength);
                if (forGradientsOnly) {
                    addSigmaTGradient(medium, -opticalLength * gradientWeight);
                }
            }
        }
        if (hit.triangle == kNoHit) {
            return tr;
        }
        medium = facing < 0.0f ? uint(interior) : sp.outsideMedium;
        // On from the boundary, aimed again at the light.
        start = sp.position;
        skipped.x = hit.triangle;
        if (!toInfinity) {
            vec3 toEnd = end - start;
            if (dot(toEnd, direction) <= 0.0f) {
                return tr;
            }
            distance = length(toEnd);
            direction = toEnd / distance;
        }
    }
    flagTruncatedLoop();
    return vec3(0.0f);
}

// Adds weight * d log T / d sigma_t for every medium in `lengths` (a shadow ray that
// shadowTransmittance recorded whole); grid segments take the density's integral at the
// ray's own gradient points.
void addRecordedTransmittanceGradients(vec3 weight, MediumLengths lengths, TrackingRandom gradientPoints) {
    for (uint i = 0u; i < lengths.count; ++i) {
        addSigmaTGradient(lengths.medium[i], -lengths.inMedium[i] * weight);
    }
    for (uint i = 0u; i < lengths.gridSegments; ++i) {
        float opticalLength =
            gridSegmentOpticalLength(P.media.v[lengths.gridMedium[i]], lengths.gridSegment[i].xyz,
                                     lengths.gridDirection[i], lengths.gridSegment[i].w, weight, gradientPoints);
        addSigmaTGradient(lengths.gridMedium[i], -opticalLength * weight);
    }
}

// The transmittance of a shadow ray whose contribution is `perUnitTransmittance` times it.
// The adjoint pass also adds delta * contribution * d log T for every medium on the way
// (on the channels in normal mode). A ray through more media or grid segments than
// MediumLengths keeps is traced a second time for them, with the same random numbers, by
// the same code in a loop: on a CPU device a shader's code runs where it stands, whether
// any lane takes it or not, and a second call would run a whole trace for every ray.
vec3 tracedShadowTransmittance(vec3 start, vec3 direction, float distance, uvec2 skipped, float leadOut, uint medium,
                               vec3 perUnitTransmittance, TrackingRandom random, TrackingRandom gradientPoints) {
    vec3 tr = vec3(0.0f);
    vec3 gradientWeight = vec3(0.0f);  // 0 for the first trace
    bool retrace = false;
    for (;;) {
        MediumLengths lengths = noMediumLengths();
        TrackingRandom tracking = random;
        TrackingRandom points = gradientPoints;
        vec3 traced =
            shadowTransmittance(start, direction, distance, skipped, leadOut, medium, gradientWeight, lengths, tracking,
                                points);
        if (retrace) {
            break;
        }
        tr = traced;
        if (!kAdjoint) {
            break;
        }
        vec3 contribution = tr * perUnitTransmittance;
        gradientWeight = delta * contribution * normalMask(adjoint);
        if (!(maxComponent(abs(gradientWeight)) > 0.0f)) {
            break;
        }
        if (lengths.complete) {
            addRecordedTransmittanceGradients(gradientWeight, lengths, gradientPoints);
            break;
        }
        retrace = true;
    }
    return tr;
}

#endif
