// Path replay backpropagation (docs/design.md, "The adjoint"). During the adjoint pass the
// radiance buffer holds L_rem, the part of the path's radiance (from the primal replay)
// not yet passed: every factor of the throughput adds delta * L_rem * d log f to the
// gradient, and every contribution C is subtracted from L_rem as the replay passes it.
//
// A factor that is zero in some channel (sigma_s = 0, base colour 0) ends that channel's
// radiance but not its derivative. The replay then keeps the channel going in
// derivative mode: its throughput becomes the path's derivative with respect to that
// one parameter (the factor replaced by its derivative), and what it later gathers is
// added straight to that parameter's gradient. Each channel follows its own parameter
// (a zero red base colour and a zero green sigma_s on one path are both followed); a
// second zero factor in a channel makes its derivative zero, as it should.
#ifndef VKDR_ADJOINT_GLSL
#define VKDR_ADJOINT_GLSL
#include "compensated_sum.glsl"
#include "fixed_point_sums.glsl"
#include "grid_tracking.glsl"
#include "scene_access.glsl"

// Factors whose gradient waits for the next segment (derivative-mode targets are in
// device_types.h).
const uint kPendingNone = 0u;
const uint kPendingBaseColor = 1u;        // Lambertian continuation weight (albedo at surfaceHit)
const uint kPendingPhaseG = 2u;           // phase-function continuation weight (pdf held fixed)

struct AdjointState {
    // Per channel, the parameter it follows in derivative mode: kTargetNone while the
    // channel is in normal mode, else the kind (kTarget*) | the parameter's index <<
    // kTargetIndexShift.
    uvec3 targets;
    uint pending;             // pending kind | index << 8
};

AdjointState loadAdjointState(uint slot) {
    uvec4 v = P.adjointState.v[slot];
    return AdjointState(v.xyz, v.w);
}

void storeAdjointState(uint slot, AdjointState s) {
    P.adjointState.v[slot] = uvec4(s.targets, s.pending);
}

vec3 derivativeMask(AdjointState s) {
    return vec3(notEqual(s.targets, uvec3(kTargetNone)));
}

vec3 normalMask(AdjointState s) {
    return vec3(1.0f) - derivativeMask(s);
}

// Bit c set where channel c is in derivative mode.
uint derivativeChannels(AdjointState s) {
    uvec3 inDerivativeMode = uvec3(notEqual(s.targets, uvec3(kTargetNone)));
    return inDerivativeMode.x | inDerivativeMode.y << 1u | inDerivativeMode.z << 2u;
}

// dLoss/dI of the path's pixel, already divided by the samples per pixel; with a
// splitSample, for a path below it the one taken at the image above it (loss.comp).
vec3 pathAdjoint(uint slot) {
    uvec4 info = P.pathInfo.v[slot];
    return P.imageAdjoint.v[info.x + (info.y < P.splitSample ? P.imagePixels : 0u)].rgb;
}

// The adjoint pass's view of the path an invocation follows; unused in the primal pass.
AdjointState adjoint;
vec3 delta;  // dLoss/dI of the path's pixel (pathAdjoint)

// The adjoint pass loads the replay state of the path in `slot`, and endReplay stores
// it; the primal pass has none.
void beginReplay(uint slot) {
    if (kAdjoint) {
        adjoint = loadAdjointState(slot);
        delta = pathAdjoint(slot);
    }
}

void endReplay(uint slot) {
    if (kAdjoint) {
        storeAdjointState(slot, adjoint);
    }
}

// The first word of sum `first` in this subgroup's copy of an accumulator whose copies
// lie `copyStride` sums apart (0 for an accumulator of one copy).
uint subgroupCopyOfSum(uint copyStride, uint first) {
    uint copy = (gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID) % kGradientCopies;
    return (copy * copyStride + first) * kFixedPointWordsPerSum;
}

// Adds the first `channels` of g to the sums first, first + 1, ... of this subgroup's
// copy (copies `copyStride` sums apart; kGradientCopies in device_types.h), each lane its
// own terms. Lanes grouped by `first` with subgroup sums (one lane adding each group's
// total) gave wrong gradients on an NVIDIA GPU, where the lanes of divergent code need
// not run a loop's subgroup operations together, and saved under 5 % of its time there
// (docs/performance.md, "NVIDIA H200").
void addGradient(Int64Buffer gradients, uint copyStride, uint first, vec4 g, uint channels) {
    uint sum = subgroupCopyOfSum(copyStride, first);
    for (uint c = 0u; c < channels; ++c) {
        addFixedPointFromOneLane(gradients, sum + c * kFixedPointWordsPerSum, g[c]);
    }
}

void addGradient(Int64Buffer gradients, uint copyStride, uint first, vec3 g, uint channels) {
    addGradient(gradients, copyStride, first, vec4(g, 0.0f), channels);
}

// Whether the pipelines add gradients of this kind (kGradientKind* in device_types.h).
// A constant: the additions of the other kinds, and what only they read, are compiled out.
bool gradientWanted(uint kind) {
    return (kGradientKinds & (1u << kind)) != 0u;
}

// Adds g times each of the point's trilinear weights (gridDensity's footprint) to the
// gradient of its voxel, in any grid (a density, emission or albedo grid): channel c of
// each voxel gets g[c] times the weight, for the grid's `channels` (1 or 3, a constant at
// every call, so that the loop unrolls). Voxels outside the grid's box are not
// parameters. The lanes of a subgroup seldom add to the same voxel, so each adds alone
// (addFixedPointFromOneLane) into its subgroup's copy of the sums.
void addTrilinearGradient(GpuDensityGrid grid, vec3 index, vec3 g, uint channels) {
    vec3 base = floor(index);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = trilinearCorner(corner);
        int voxel = gridVoxelOffset(grid, ivec3(base) + offset);
        if (voxel >= 0) {
            vec3 weighted = g * trilinearWeight(index - base, offset);
            for (uint c = 0u; c < channels; ++c) {
                addFixedPointFromOneLane(P.densityGradients,
                                         subgroupCopyOfSum(P.densityGradientsCopyStride, uint(voxel) + c), weighted[c]);
            }
        }
    }
}

void addTrilinearDensityGradient(GpuDensityGrid grid, vec3 index, float g) {
    if (gradientWanted(kGradientKindDensity)) {
        addTrilinearGradient(grid, index, vec3(g), 1u);
    }
}

// The first of the sums a gradient with respect to sigma_t = sigma_a + sigma_s adds to.
// Where both are wanted, their sigma_t sums, which gradient_values.comp adds to each (the
// same total, bit for bit, as adding every term to both, at half the additions);
// otherwise the sums of the one wanted.
uint sigmaTSums() {
    if (gradientWanted(kGradientKindSigmaA)) {
        return gradientWanted(kGradientKindSigmaS) ? kMediumGradientSigmaT : kMediumGradientSigmaA;
    }
    return kMediumGradientSigmaS;
}

// An invocation's terms of one medium's gradient, held until its stage ends
// (flushMediumGradients). A segment through a homogeneous medium adds to the same few sums
// from its free flight, its equiangular next event, its shadow ray and its phase function,
// and every addition to device memory costs subgroup sums over the words of its sums
// (addFixedPoint): held, each sum takes one. Terms of other media are added at once. An
// invocation sums its terms in the same order in every run and whatever else is wanted
// (sigma_t's terms apart from sigma_s's), so totals keep their bits.
struct HeldMediumGradients {
    uint medium;  // kNoMediumIndex: nothing held
    vec3 sigmaS;
    vec4 gAndSigmaT;  // x: g; yzw: sigma_t (kMediumGradientG, then kMediumGradientSigmaT)
    vec3 emission;
};

HeldMediumGradients heldMediumGradients = HeldMediumGradients(kNoMediumIndex, vec3(0.0f), vec4(0.0f), vec3(0.0f));

// The stage holds the terms of `medium` (the medium of its segment, or the one its shadow
// ray starts in).
void holdMediumGradients(uint medium) {
    heldMediumGradients.medium = medium;
}

// Adds `values` to the sums of `medium` from `component`, where any lane of the subgroup
// has a term for them.
void addHeldMediumSums(uint medium, uint component, vec4 values, uint channels) {
    if (subgroupBallot(any(notEqual(values, vec4(0.0f)))) != uvec4(0u)) {
        addGradient(P.mediumGradients, P.mediumGradientsCopyStride, medium * kMediumGradientStride + component,
                    values, channels);
    }
}

// Adds the held terms to their medium's sums: every stage that holds a medium's terms
// calls it before it ends.
void flushMediumGradients() {
    if (!kAdjoint || heldMediumGradients.medium == kNoMediumIndex) {
        return;
    }
    HeldMediumGradients held = heldMediumGradients;
    if (gradientWanted(kGradientKindSigmaS)) {
        addHeldMediumSums(held.medium, kMediumGradientSigmaS, vec4(held.sigmaS, 0.0f), 3u);
    }
    if (sigmaTSums() == kMediumGradientSigmaT) {
        addHeldMediumSums(held.medium, kMediumGradientG, held.gAndSigmaT, 4u);
    } else {
        if (gradientWanted(kGradientKindG)) {
            addHeldMediumSums(held.medium, kMediumGradientG, vec4(held.gAndSigmaT.x, 0.0f, 0.0f, 0.0f), 1u);
        }
        if (gradientWanted(kGradientKindSigmaA) || gradientWanted(kGradientKindSigmaS)) {
            addHeldMediumSums(held.medium, sigmaTSums(), vec4(held.gAndSigmaT.yzw, 0.0f), 3u);
        }
    }
    if (gradientWanted(kGradientKindMediumEmission)) {
        addHeldMediumSums(held.medium, kMediumGradientEmission, vec4(held.emission, 0.0f), 3u);
    }
}

// Adds g to the sums of `medium` from `component` (a kMediumGradient* offset), or holds
// it where `medium` is held and the component has a place in HeldMediumGradients.
void addMediumGradient(uint medium, uint component, vec3 g, uint channels) {
    bool held = medium == heldMediumGradients.medium;
    if (held && component == kMediumGradientSigmaS) {
        heldMediumGradients.sigmaS += g;
    } else if (held && component == kMediumGradientG) {
        heldMediumGradients.gAndSigmaT.x += g.x;
    } else if (held && component == kMediumGradientSigmaT) {
        heldMediumGradients.gAndSigmaT.yzw += g;
    } else if (held && component == kMediumGradientEmission) {
        heldMediumGradients.emission += g;
    } else {
        uint sums = component == kMediumGradientSigmaT ? sigmaTSums() : component;
        addGradient(P.mediumGradients, P.mediumGradientsCopyStride, medium * kMediumGradientStride + sums, g,
                    channels);
    }
}

void addSigmaSGradient(uint medium, vec3 dSigmaS) {
    if (gradientWanted(kGradientKindSigmaS)) {
        addMediumGradient(medium, kMediumGradientSigmaS, dSigmaS, 3u);
    }
}

// A gradient with respect to sigma_t = sigma_a + sigma_s (sigmaTSums).
void addSigmaTGradient(uint medium, vec3 dSigmaT) {
    if (gradientWanted(kGradientKindSigmaA) || gradientWanted(kGradientKindSigmaS)) {
        addMediumGradient(medium, kMediumGradientSigmaT, dSigmaT, 3u);
    }
}

void addPhaseGGradient(uint medium, float g) {
    if (gradientWanted(kGradientKindG)) {
        addMediumGradient(medium, kMediumGradientG, vec3(g, 0.0f, 0.0f), 1u);
    }
}

void addMediumEmissionGradient(uint medium, vec3 g) {
    if (gradientWanted(kGradientKindMediumEmission)) {
        addMediumGradient(medium, kMediumGradientEmission, g, 3u);
    }
}

void addBaseColorGradient(uint material, vec3 g) {
    if (gradientWanted(kGradientKindBaseColor)) {
        addGradient(P.baseColorGradients, P.baseColorGradientsCopyStride, material * kColorGradientStride, g, 3u);
    }
}

void addEmissionGradient(uint material, vec3 g) {
    if (gradientWanted(kGradientKindEmission)) {
        addGradient(P.emissionGradients, P.emissionGradientsCopyStride, material * kColorGradientStride, g, 3u);
    }
}

void addLightIntensityGradient(uint light, vec3 g) {
    if (gradientWanted(kGradientKindLightIntensity)) {
        addGradient(P.lightGradients, P.lightGradientsCopyStride, light * kColorGradientStride, g, 3u);
    }
}

// The gradient of an emitter's parameter: a material's emission or a punctual light's
// intensity (`emitter` as in LightArrival.emitter).
void addEmitterGradient(uint emitter, vec3 g) {
    if ((emitter & kPunctualEmitter) != 0u) {
        addLightIntensityGradient(P.punctualLights.v[emitter & ~kPunctualEmitter].light, g);
    } else {
        addEmissionGradient(emitter, g);
    }
}

// g = dLoss/d(texture value at uv), spread over the texels the lookup blends.
void addTexelGradients(TextureMap map, vec2 uv, vec3 g) {
    BilinearFootprint footprint = bilinearFootprint(map, uv);
    for (int corner = 0; corner < 4; ++corner) {
        addGradient(P.texelGradients, P.texelGradientsCopyStride, footprint.texel[corner] * kColorGradientStride,
                    g * footprint.weight[corner], 3u);
    }
}

// g = dLoss/d albedo at the surface point `hit` (t, b1, b2, triangle bits). albedo = base
// colour factor * texture(uv) * vertex colour, so the factor gets g * texture(uv) *
// colour and the base colour texture's texels g * factor * colour.
void addAlbedoGradient(uint material, vec4 hit, vec3 g) {
    uint triangle = floatBitsToUint(hit.w);
    vec2 uv = surfaceUv(triangle, hit.y, hit.z);
    vec3 colored = g * vertexColor(triangle, hit.y, hit.z);
    GpuMaterial m = P.materials.v[material];
    addBaseColorGradient(material, colored * baseColorTexture(m, uv));
    if (gradientWanted(kGradientKindBaseColorTexture) && m.baseColorTexture >= 0) {
        addTexelGradients(baseColorMap(m), uv, colored * m.baseColor.rgb);
    }
}

// g = the gradient gathered by a path's derivative channels: channel c's part goes to
// the parameter it follows, once for all the channels that follow the same one. A
// density grid's point adds to the voxels around the path's densityTargetPoint. An
// albedo grid's point is the channel's own (channels may meet a zero albedo at
// different collisions): channel c adds to channel c of the voxels around it.
void addTargetGradient(uint slot, vec3 g) {
    for (uint c = 0u; c < 3u; ++c) {
        uint target = adjoint.targets[c];
        uint kind = target & ((1u << kTargetIndexShift) - 1u);
        uint index = target >> kTargetIndexShift;
        if (kind == kTargetAlbedoPoint) {
            if (gradientWanted(kGradientKindAlbedoGrid)) {
                vec3 part = vec3(0.0f);
                part[c] = g[c];
                addTrilinearGradient(P.densityGrids.v[index], P.albedoTargetPoints.v[slot * 3u + c].xyz, part, 3u);
            }
            continue;
        }
        bool followedByAnEarlierChannel = (c > 0u && adjoint.targets[0] == target) ||
                                          (c > 1u && adjoint.targets[1] == target);
        if (target == kTargetNone || followedByAnEarlierChannel) {
            continue;
        }
        vec3 part = g * vec3(equal(adjoint.targets, uvec3(target)));
        if (kind == kTargetMediumScattering) {
            addSigmaSGradient(index, part);
        } else if (kind == kTargetDensityPoint) {
            addTrilinearDensityGradient(P.densityGrids.v[index], P.densityTargetPoint.v[slot].xyz,
                                        part.x + part.y + part.z);
        } else {
            addBaseColorGradient(index, part);
        }
    }
}

// The path gathers a contribution C. The primal pass adds it to the path's radiance.
// The replay passes it: normal channels leave it behind in L_rem, derivative channels
// add it to their parameter's gradient. L and L_rem are compensated sums
// (compensated_sum.glsl), the replay subtracting the very floats the primal pass added.
void gather(uint slot, vec3 c) {
    vec3 passed = c;
    if (kAdjoint) {
        passed = -c * normalMask(adjoint);
        addTargetGradient(slot, delta * c * derivativeMask(adjoint));
    }
    CompensatedSum radiance = CompensatedSum(P.radiance.v[slot].rgb, P.radianceRounding.v[slot].rgb);
    radiance = addCompensated(radiance, passed);
    P.radiance.v[slot].rgb = radiance.high;
    P.radianceRounding.v[slot].rgb = radiance.low;
}

// delta * L_rem * d log f / d theta on the normal channels, for a factor f that
// multiplies everything the path gathers from here on.
vec3 factorGradient(uint slot, vec3 dLogF) {
    return delta * P.radiance.v[slot].rgb * dLogF * normalMask(adjoint);
}

// d log f / d f, per channel, for the log-derivative of a factor linear in f; 0 where f
// is 0, whose gradient derivative mode finds instead.
vec3 logDerivativeOfLinear(vec3 f) {
    return vec3(f.x > 0.0f ? 1.0f / f.x : 0.0f, f.y > 0.0f ? 1.0f / f.y : 0.0f, f.z > 0.0f ? 1.0f / f.z : 0.0f);
}

// Channels where `factor` is zero and the path is still in normal mode switch to
// derivative mode for (kind, index), carrying `derivative` (the factor's derivative,
// times the throughput before it) instead of zero. Returns the new throughput; `entered`
// says which channels switched, for targets that keep a point per switch.
vec3 enterDerivativeMode(vec3 betaAfter, vec3 factor, vec3 derivative, uint kind, uint index, out bvec3 entered) {
    entered = bvec3(false);
    bool wanted = kind == kTargetMediumScattering ? gradientWanted(kGradientKindSigmaS)
                  : kind == kTargetDensityPoint ? gradientWanted(kGradientKindDensity)
                  : kind == kTargetAlbedoPoint
                      ? gradientWanted(kGradientKindAlbedoGrid)
                      : gradientWanted(kGradientKindBaseColor) || gradientWanted(kGradientKindBaseColorTexture);
    if (!wanted) {
        return betaAfter;  // no gradient of this kind is wanted: the path ends as in the primal pass
    }
    for (uint c = 0u; c < 3u; ++c) {
        if (factor[c] == 0.0f && adjoint.targets[c] == kTargetNone && derivative[c] != 0.0f) {
            adjoint.targets[c] = kind | index << kTargetIndexShift;
            betaAfter[c] = derivative[c];
            entered[c] = true;
        }
    }
    return betaAfter;
}

// The throughput after a factor parameter * rest that is linear in a differentiable
// parameter (a base colour, sigma_s) of kind `targetKind`. Where the parameter is zero
// the adjoint pass goes on in derivative mode.
vec3 multiplyByParameter(vec3 beta, vec3 parameter, vec3 rest, uint targetKind, uint index) {
    vec3 after = beta * (parameter * rest);
    if (kAdjoint) {
        bvec3 entered;
        after = enterDerivativeMode(after, parameter, beta * rest, targetKind, index, entered);
    }
    return after;
}

// The previous vertex's continuation factor: its gradient needs L_rem after that
// vertex's next-event contribution, which the shadow stage has subtracted by now.
void applyPendingFactor(uint slot) {
    if (!kAdjoint) {
        return;
    }
    uint kind = adjoint.pending & 0xffu;
    if (kind == kPendingNone) {
        return;
    }
    uint index = adjoint.pending >> 8u;
    vec3 g = factorGradient(slot, P.pendingFactor.v[slot].rgb);
    if (kind == kPendingBaseColor) {
        addAlbedoGradient(index, P.surfaceHit.v[slot], g);
    } else {
        addPhaseGGradient(index, g.x + g.y + g.z);
    }
    adjoint.pending = kPendingNone;
}

// Adjoint pass: the continuation factor of this vertex, whose gradient waits for the
// next segment (applyPendingFactor).
void setPendingFactor(uint slot, uint kind, uint index, vec3 dLogF) {
    if (kAdjoint) {
        adjoint.pending = kind | (index << 8u);
        P.pendingFactor.v[slot] = vec4(dLogF, 0.0f);
    }
}

// What Russian roulette looks at: in the replay, the channels the primal pass still
// carries, so that it takes the same decisions; derivative channels only ride along.
vec3 rouletteThroughput(vec3 beta) {
    if (!kAdjoint) {
        return beta;
    }
    vec3 primal = beta * normalMask(adjoint);
    return maxComponent(primal) > 0.0f ? primal : beta;
}

#endif
