#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 4: one vertex per path. Surfaces: pass through medium boundaries, add emission
// (MIS against the BSDF pdf), next-event estimation, cosine sampling of the Lambertian
// BSDF. Medium vertices: next-event estimation (weighted against equiangular sampling,
// distance_mis.glsl), exact Henyey-Greenstein sampling.
// Pauses of tracking through a density grid: the same ray again from where it stopped.
// Then Russian roulette and the next ray. The adjoint pass replays the same decisions,
// passes each contribution, and records the continuation factor's log-derivative for
// the next segment (adjoint.glsl).
// Each end of the shade queue has a pipeline of its own (kQueueEnd): medium vertices
// and pauses at the front, surface vertices at the back, so that neither runs the
// other's code (a CPU device runs every branch of a shader, taken or not).
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/path_state.glsl"
#include "lib/scene_access.glsl"
#include "lib/lights.glsl"
#include "lib/phase_hg.glsl"
#include "lib/adjoint.glsl"
#include "lib/distance_mis.glsl"

uint nextRayQueue() {
    return pass.currentRays == kQueueRays0 ? kQueueRays1 : kQueueRays0;
}

// Queues the next segment of the path from `start` along `direction`, leaving the
// triangle `leftTriangle` (kNoHit: none).
void continuePath(uint slot, PathInfo info, vec3 start, vec3 direction, uint leftTriangle, uint medium) {
    ++info.segment;
    if (info.segment >= P.segmentLimit) {
        atomicAdd(P.queueCounters.c.truncatedPaths, 1u);
        return;
    }
    storePathInfo(slot, info);
    storeRay(slot, start, direction, leftTriangle);
    P.vertexInfo.v[slot].x = medium;
    queueRay(nextRayQueue(), slot, medium);
}

// Russian roulette after the first scattering vertex, as in pbrt: survive with
// probability max(beta), reweighting the survivors. Returns false to end the path.
bool survivesRoulette(inout vec3 beta, uint depth, float u) {
    vec3 decisive = rouletteThroughput(beta);
    float q = max(0.0f, 1.0f - maxComponent(decisive));
    if (depth > 1u && q > 0.0f) {
        if (u < q) {
            return false;
        }
        beta /= 1.0f - q;
    }
    return maxComponent(beta) > 0.0f;
}

// A vertex and what its next-event estimate needs to know.
struct NextEventQuery {
    vec3 position;     // the vertex: where the shadow ray starts
    uint medium;       // medium the shadow ray starts in
    vec3 beta;
    uint vertexKind;
    uint index;        // material (surface) or medium (medium vertex)
    uint triangle;     // a surface vertex's, which the shadow ray leaves; kNoHit at a medium vertex
};

// Queues a shadow ray towards a sampled light carrying its MIS-weighted, unoccluded
// contribution beta * scatter * Le * w / pdf. `scatter` is f * cos (surface) or the
// phase value (medium) for the direction light.wi; `scatterPdf` is the density the other
// strategy would have sampled it with. For the adjoint, `dScatter` is d scatter / d albedo
// (surface) and `dLogPhase` is d log phase / d g (medium).
void nextEvent(uint slot, NextEventQuery query, LightArrival light, vec3 scatter, float scatterPdf, vec3 dScatter,
               float dLogPhase) {
    vec3 le = light.parameter * light.perUnit;
    bool contributes = maxComponent(le * scatter) > 0.0f;
    // The emitter's own gradient is wanted even where its parameter is 0.
    bool hasGradient = kAdjoint && (maxComponent(le * dScatter) > 0.0f || maxComponent(light.perUnit * scatter) > 0.0f);
    if (light.pdf <= 0.0f || !(contributes || hasGradient)) {
        return;
    }
    float weight = lightSampleWeight(light, scatterPdf);
    ShadowRay ray = shadowRay(light, query.position);
    P.shadowOrigin.v[slot] = vec4(query.position, ray.distance);
    P.shadowEnds.v[slot] = vec4(uintBitsToFloat(query.triangle), uintBitsToFloat(ray.endTriangle), ray.leadOut, 0.0f);
    P.shadowDirection.v[slot] = vec4(ray.direction, uintBitsToFloat(query.medium));
    // The segment keys the random numbers of ratio tracking through density grids.
    P.shadowContribution.v[slot] = vec4(query.beta * scatter * le * weight, uintBitsToFloat(P.pathInfo.v[slot].w));
    if (kAdjoint) {
        P.shadowScatterGradient.v[slot] = vec4(query.beta * dScatter * le * weight, dLogPhase);
        P.shadowEmissionGradient.v[slot] =
            vec4(query.beta * scatter * light.perUnit * weight, uintBitsToFloat(light.emitter));
        P.shadowVertex.v[slot] = uvec4(query.vertexKind, query.index, derivativeChannels(adjoint), 0u);
    }
    queuePush(kQueueShadow, slot);
}

LightArrival sampleLightFor(PathInfo info, vec3 from) {
    return lightArrival(sampleLight(segmentRandom(info, kDimLight).xyz, from), from);
}

void shadeSurface(uint slot, PathInfo info, vec3 beta, vec3 direction, vec4 hit, uint medium) {
    uint triangle = floatBitsToUint(hit.w);
    SurfacePoint sp = surfacePoint(triangle, hit.y, hit.z);
    GpuMaterial material = P.materials.v[sp.material];
    if (material.interiorMedium >= 0) {
        // A boundary changes the medium only: no vertex, no depth, same MIS vertex.
        bool entering = dot(direction, sp.normal) < 0.0f;
        continuePath(slot, info, sp.position, direction, triangle,
                     entering ? uint(material.interiorMedium) : sp.outsideMedium);
        return;
    }
    vec3 toViewer = -direction;
    vec3 lePerUnit = emissionPerUnit(material, sp.normal, sp.uv, toViewer);
    vec3 le = material.emission.rgb * lePerUnit;
    if (maxComponent(le) > 0.0f || kAdjoint) {
        vec4 mis = P.misVertex.v[slot];
        float weight = 1.0f;
        if (mis.w > 0.0f) {
            float pdfArea = P.triangleInfo.v[triangle].lightPmf / sp.area;
            weight = powerHeuristic(mis.w, nextEventPdf(triangle, pdfArea, mis.xyz, sp.position, sp.normal));
        }
        gather(slot, beta * le * weight);
        if (kAdjoint) {
            addEmissionGradient(sp.material, delta * beta * lePerUnit * weight * normalMask(adjoint));
        }
    }
    if (info.depth == P.maxDepth) {
        return;
    }
    ++info.depth;
    vec3 n = dot(sp.normal, toViewer) > 0.0f ? sp.normal : -sp.normal;
    // The Lambertian lobe follows the shading normal; directions below the geometric
    // surface get nothing, so no light leaks through it.
    vec3 ns = shadingNormal(triangle, hit.y, hit.z, n);
    // The albedo's factors but the base colour factor, a parameter: its texture and the
    // vertex colour.
    vec3 texture = baseColorTexture(material, sp.uv) * vertexColor(triangle, hit.y, hit.z);
    vec3 albedo = material.baseColor.rgb * texture;
    if (kAdjoint) {
        P.surfaceHit.v[slot] = hit;
    }
    if (P.lightCount > 0u) {
        // Measured from the surface itself; only the shadow ray starts off it.
        LightArrival light = sampleLightFor(info, sp.position);
        float cosine = dot(ns, light.wi);
        if (cosine > 0.0f && dot(n, light.wi) > 0.0f) {
            nextEvent(slot, NextEventQuery(sp.position, medium, beta, kVertexSurface, sp.material, triangle), light,
                      albedo * (kInvPi * cosine), kInvPi * cosine, vec3(kInvPi * cosine), 0.0f);
        }
    }
    vec4 u = segmentRandom(info, kDimScatter);
    vec3 wi = frameFromNormal(ns) * sampleCosineHemisphere(u.xy);
    if (dot(n, wi) <= 0.0f) {
        return;
    }
    setPendingFactor(slot, kPendingBaseColor, sp.material, logDerivativeOfLinear(albedo));
    beta = multiplyByParameter(beta, material.baseColor.rgb, texture, kTargetBaseColor, sp.material);
    if (!survivesRoulette(beta, info.depth, u.z)) {
        return;
    }
    P.beta.v[slot].rgb = beta;
    P.misVertex.v[slot] = vec4(sp.position, max(dot(ns, wi), 0.0f) * kInvPi);
    continuePath(slot, info, sp.position, wi, triangle, medium);
}

void shadeMedium(uint slot, PathInfo info, vec3 beta, vec3 origin, vec3 direction, vec4 hit, uint medium) {
    if (info.depth == P.maxDepth) {
        return;
    }
    ++info.depth;
    vec3 position = origin + direction * hit.x;
    GpuMedium m = P.media.v[medium];
    float g = m.g;
    if (P.lightCount > 0u) {
        LightArrival light = sampleLightFor(info, position);
        float mu = dot(direction, light.wi);
        float phase = hgPhase(mu, g);
        // hit.y: where the segment that found this collision ends.
        float distanceWeight = freeFlightNextEventWeight(m, origin, direction, hit.y, hit.x, light);
        NextEventQuery query =
            NextEventQuery(position, medium, beta * distanceWeight, kVertexMedium, medium, kNoHit);
        nextEvent(slot, query, light, vec3(phase), phase, vec3(0.0f), hgPhaseDLogG(mu, g));
    }
    vec4 u = segmentRandom(info, kDimScatter);
    vec3 wi = sampleHg(direction, g, u.xy);
    float mu = dot(direction, wi);
    setPendingFactor(slot, kPendingPhaseG, medium, vec3(hgPhaseDLogG(mu, g)));
    if (!survivesRoulette(beta, info.depth, u.z)) {
        return;
    }
    P.beta.v[slot].rgb = beta;
    P.misVertex.v[slot] = vec4(position, hgPhase(mu, g));
    continuePath(slot, info, position, wi, kNoHit, medium);
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= endSize(kQueueShade)) {
        return;
    }
    uint slot = endItem(kQueueShade, index);
    PathInfo info = loadPathInfo(slot);
    vec3 beta = P.beta.v[slot].rgb;
    vec3 direction = P.rayDirection.v[slot].xyz;
    vec4 hit = P.hit.v[slot];
    uvec4 vertex = P.vertexInfo.v[slot];
    beginReplay(slot);
    if (kQueueEnd == kBackEnd) {
        shadeSurface(slot, info, beta, direction, hit, vertex.x);
    } else if (kDensityGrids && vertex.y == kVertexPause) {
        continuePath(slot, info, P.rayOrigin.v[slot].xyz + direction * hit.x, direction, kNoHit, vertex.x);
    } else {
        shadeMedium(slot, info, beta, P.rayOrigin.v[slot].xyz, direction, hit, vertex.x);
    }
    endReplay(slot);
}
