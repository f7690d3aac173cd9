#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 4: one vertex per path. Surfaces: pass through medium boundaries, add emission
// (MIS against the BSDF pdf), next-event estimation, cosine sampling of the Lambertian
// BSDF. Medium vertices: next-event estimation, exact Henyey-Greenstein sampling.
// Then Russian roulette and the next ray.
#include "lib/stage_common.glsl"
#include "lib/queues.glsl"
#include "lib/path_state.glsl"
#include "lib/scene_access.glsl"
#include "lib/lights.glsl"
#include "lib/phase_hg.glsl"

uint nextRayQueue() {
    return pass.currentRays == kQueueRays0 ? kQueueRays1 : kQueueRays0;
}

// Queues the next segment of the path from `origin` along `direction`.
void continuePath(uint slot, PathInfo info, vec3 origin, vec3 direction, uint medium) {
    ++info.segment;
    if (info.segment >= P.segmentLimit) {
        atomicAdd(P.queueCounters.c.truncatedPaths, 1u);
        return;
    }
    storePathInfo(slot, info);
    storeRay(slot, origin, direction);
    P.vertexInfo.v[slot].x = medium;
    queuePush(nextRayQueue(), slot);
}

// Russian roulette after the first scattering vertex, as in pbrt: survive with
// probability max(beta), reweighting the survivors. Returns false to end the path.
bool survivesRoulette(inout vec3 beta, uint depth, float u) {
    float q = max(0.0f, 1.0f - maxComponent(beta));
    if (depth > 1u && q > 0.0f) {
        if (u < q) {
            return false;
        }
        beta /= 1.0f - q;
    }
    return maxComponent(beta) > 0.0f;
}

// Samples a point on an emitter and queues a shadow ray carrying its MIS-weighted
// contribution; `scatter` is f * cos (surface) or the phase value (medium) towards the
// light, `scatterPdf` the density the other strategy would have sampled it with.
struct NextEventQuery {
    vec3 position;
    uint medium;
    vec3 beta;
};

void nextEvent(uint slot, PathInfo info, NextEventQuery query, vec3 wi, vec3 lightPoint,
               vec3 le, float pdfLight, vec3 scatter, float scatterPdf) {
    if (pdfLight <= 0.0f || maxComponent(le * scatter) <= 0.0f) {
        return;
    }
    float weight = powerHeuristic(pdfLight, scatterPdf);
    float distance = length(lightPoint - query.position) - 2.0f * P.rayEpsilon;
    P.shadowOrigin.v[slot] = vec4(query.position, distance);
    P.shadowDirection.v[slot] = vec4(wi, uintBitsToFloat(query.medium));
    P.shadowContribution.v[slot] = vec4(query.beta * scatter * le * (weight / pdfLight), 0.0f);
    queuePush(kQueueShadow, slot);
}

LightSample sampleLightFrom(PathInfo info, vec3 position, out vec3 wi, out vec3 le, out float pdfLight) {
    LightSample ls = sampleLight(segmentRandom(info, kDimLight).xyz);
    wi = normalize(ls.position - position);
    le = emittedRadiance(P.materials.v[ls.material], ls.normal, ls.uv, -wi);
    pdfLight = lightPdfSolidAngle(ls.pdfArea, position, ls.position, ls.normal);
    return ls;
}

void shadeSurface(uint slot, PathInfo info, vec3 beta, vec3 direction, vec4 hit, uint medium) {
    SurfacePoint sp = surfacePoint(floatBitsToUint(hit.w), hit.y, hit.z);
    GpuMaterial material = P.materials.v[sp.material];
    if (material.interiorMedium >= 0) {
        // A boundary changes the medium only: no vertex, no depth, same MIS vertex.
        bool entering = dot(direction, sp.normal) < 0.0f;
        vec3 side = entering ? -sp.normal : sp.normal;
        continuePath(slot, info, sp.position + side * P.rayEpsilon, direction,
                     entering ? uint(material.interiorMedium) : sp.outsideMedium);
        return;
    }
    vec3 toViewer = -direction;
    vec3 le = emittedRadiance(material, sp.normal, sp.uv, toViewer);
    if (maxComponent(le) > 0.0f) {
        vec4 mis = P.misVertex.v[slot];
        float weight = 1.0f;
        if (mis.w > 0.0f) {
            float pdfArea = P.triangleInfo.v[floatBitsToUint(hit.w)].lightPmf / sp.area;
            weight = powerHeuristic(mis.w, lightPdfSolidAngle(pdfArea, mis.xyz, sp.position, sp.normal));
        }
        addRadiance(slot, beta * le * weight);
    }
    if (info.depth == P.maxDepth) {
        return;
    }
    ++info.depth;
    vec3 n = dot(sp.normal, toViewer) > 0.0f ? sp.normal : -sp.normal;
    vec3 albedo = materialAlbedo(material, sp.uv);
    vec3 origin = sp.position + n * P.rayEpsilon;
    if (P.lightCount > 0u) {
        vec3 wi;
        vec3 lightLe;
        float pdfLight;
        LightSample ls = sampleLightFrom(info, origin, wi, lightLe, pdfLight);
        float cosine = dot(n, wi);
        if (cosine > 0.0f) {
            nextEvent(slot, info, NextEventQuery(origin, medium, beta), wi, ls.position, lightLe,
                      pdfLight, albedo * (kInvPi * cosine), kInvPi * cosine);
        }
    }
    vec4 u = segmentRandom(info, kDimScatter);
    vec3 wi = frameFromNormal(n) * sampleCosineHemisphere(u.xy);
    beta *= albedo;
    if (!survivesRoulette(beta, info.depth, u.z)) {
        return;
    }
    P.beta.v[slot].rgb = beta;
    P.misVertex.v[slot] = vec4(sp.position, max(dot(n, wi), 0.0f) * kInvPi);
    continuePath(slot, info, origin, wi, medium);
}

void shadeMedium(uint slot, PathInfo info, vec3 beta, vec3 origin, vec3 direction, vec4 hit, uint medium) {
    if (info.depth == P.maxDepth) {
        return;
    }
    ++info.depth;
    vec3 position = origin + direction * hit.x;
    float g = P.media.v[medium].g;
    if (P.lightCount > 0u) {
        vec3 wi;
        vec3 lightLe;
        float pdfLight;
        LightSample ls = sampleLightFrom(info, position, wi, lightLe, pdfLight);
        float phase = hgPhase(dot(direction, wi), g);
        nextEvent(slot, info, NextEventQuery(position, medium, beta), wi, ls.position, lightLe,
                  pdfLight, vec3(phase), phase);
    }
    vec4 u = segmentRandom(info, kDimScatter);
    vec3 wi = sampleHg(direction, g, u.xy);
    if (!survivesRoulette(beta, info.depth, u.z)) {
        return;
    }
    P.beta.v[slot].rgb = beta;
    P.misVertex.v[slot] = vec4(position, hgPhase(dot(direction, wi), g));
    continuePath(slot, info, position, wi, medium);
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= queueSize(kQueueShade)) {
        return;
    }
    uint slot = queueItem(kQueueShade, index);
    PathInfo info = loadPathInfo(slot);
    vec3 beta = P.beta.v[slot].rgb;
    vec3 direction = P.rayDirection.v[slot].xyz;
    vec4 hit = P.hit.v[slot];
    uvec4 vertex = P.vertexInfo.v[slot];
    if (vertex.y == kVertexMedium) {
        shadeMedium(slot, info, beta, P.rayOrigin.v[slot].xyz, direction, hit, vertex.x);
    } else {
        shadeSurface(slot, info, beta, direction, hit, vertex.x);
    }
}
