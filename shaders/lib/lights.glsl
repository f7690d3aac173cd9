// The lights of next-event estimation: emissive triangles and punctual lights (point,
// spot, directional), chosen in proportion to their power (host-built CDF).
#ifndef VKDR_LIGHTS_GLSL
#define VKDR_LIGHTS_GLSL
#include "scene_access.glsl"
#include "sampling.glsl"

const uint kNoPunctualLight = 0xffffffffu;

struct LightSample {
    vec3 position;   // on the emitter, or the punctual light's position
    vec3 normal;     // the emitter's geometric normal
    vec2 uv;
    uint material;   // the emitter's material
    float pdfArea;   // pmf of the triangle / its area; a punctual light's pmf
    uint punctual;   // index into P.punctualLights, or kNoPunctualLight for a triangle
    uint triangle;   // the emitter triangle, kNoHit for a punctual light
};

// First index i with cdf[i + 1] > u, by binary search (log2 of the light count steps).
uint findLight(float u) {
    uint lo = 0u;
    uint hi = P.lightCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (P.lightCdf.v[mid + 1u] > u) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

LightSample sampleLight(vec3 u) {
    uint source = P.lightSources.v[findLight(u.x)];
    if ((source & kPunctualEmitter) != 0u) {
        uint index = source & ~kPunctualEmitter;
        GpuPunctualLight light = P.punctualLights.v[index];
        return LightSample(light.position, vec3(0.0f), vec2(0.0f), 0u, light.pmf, index, kNoHit);
    }
    vec2 b = sampleUniformTriangle(u.yz);
    SurfacePoint sp = surfacePoint(source, b.x, b.y);
    return LightSample(sp.position, sp.normal, sp.uv, sp.material,
                       P.triangleInfo.v[source].lightPmf / sp.area, kNoPunctualLight, source);
}

// Solid-angle density of reaching a point on an emitter from `from` by light sampling.
float lightPdfSolidAngle(float pdfArea, vec3 from, vec3 lightPosition, vec3 lightNormal) {
    vec3 d = lightPosition - from;
    float dist2 = dot(d, d);
    float cosLight = abs(dot(lightNormal, d)) / sqrt(dist2);
    return cosLight > 0.0f ? pdfArea * dist2 / cosLight : 0.0f;
}

// glTF's spot cone (KHR_lights_punctual): full intensity inside the inner cone, none
// outside the outer one, and between them the square of a linear ramp in the cosine.
float spotFalloff(GpuPunctualLight light, float cosAngle) {
    float ramp = (cosAngle - light.cosOuterCone) / max(light.cosInnerCone - light.cosOuterCone, 1e-3f);
    float t = clamp(ramp, 0.0f, 1.0f);
    return t * t;
}

// What a light sample sends towards `from`: its direction and distance, the radiance
// arriving (from a punctual light: the irradiance on a plane facing it) per unit of the
// emitter's parameter (emission or intensity), that parameter, and the density of the
// sample in solid angle, or for a punctual light its pmf, the weight of a delta.
struct LightArrival {
    vec3 wi;
    float distance;
    vec3 perUnit;
    vec3 parameter;
    float pdf;
    bool isDelta;   // a punctual light: no other strategy finds it, so no MIS
    uint emitter;   // the material, or kPunctualEmitter | the punctual light
    vec3 end;            // the light's point, where shadow rays towards a sample at a finite distance end
    uint endTriangle;    // the emitter triangle it lies on, which they pass over; kNoHit
    float leadOut;       // the stretch before a punctual light: not traced, in the medium there
};

// The factor of a next event's contribution beta * scatter * Le * this: the power
// heuristic's weight against the scattering strategy, which would find the light with
// density `scatterPdf` (none finds a punctual light), over the light sample's density.
float lightSampleWeight(LightArrival light, float scatterPdf) {
    return (light.isDelta ? 1.0f : powerHeuristic(light.pdf, scatterPdf)) / light.pdf;
}

// The part of a shadow ray's length by which it stops short of a point or spot light,
// and the least it stops short by relative to the light's coordinates: a surface point
// there is rounded by a few units in their last place (1e-7 each).
const float kShadowEpsilon = 1.0e-4f;
const float kLightOffsetPerMagnitude = 1.0e-5f;

// A shadow ray: its direction and length to the light (kFar towards a directional
// light), the emitter triangle it ends on, and its lead-out, the end of that length left
// untraced (LightArrival).
struct ShadowRay {
    vec3 direction;
    float distance;
    uint endTriangle;
    float leadOut;
};

// The shadow ray of a light sample from the vertex lit at `start`: to the light's
// point, or along the light's direction without end.
ShadowRay shadowRay(LightArrival light, vec3 start) {
    if (light.distance >= kFar) {
        return ShadowRay(light.wi, kFar, kNoHit, 0.0f);
    }
    vec3 toEnd = light.end - start;
    float distance = length(toEnd);
    return distance > 0.0f ? ShadowRay(toEnd / distance, distance, light.endTriangle, min(light.leadOut, distance))
                           : ShadowRay(light.wi, 0.0f, kNoHit, 0.0f);
}

LightArrival lightArrival(LightSample ls, vec3 from) {
    LightArrival a;
    if (ls.punctual == kNoPunctualLight) {
        a.wi = normalize(ls.position - from);
        a.distance = length(ls.position - from);
        GpuMaterial light = P.materials.v[ls.material];
        a.perUnit = emissionPerUnit(light, ls.normal, ls.uv, -a.wi);
        a.parameter = light.emission.rgb;
        a.pdf = lightPdfSolidAngle(ls.pdfArea, from, ls.position, ls.normal);
        a.isDelta = false;
        a.emitter = ls.material;
        a.end = ls.position;
        a.endTriangle = ls.triangle;
        a.leadOut = 0.0f;
        return a;
    }
    GpuPunctualLight light = P.punctualLights.v[ls.punctual];
    a.parameter = light.intensity;
    a.pdf = ls.pdfArea;
    a.isDelta = true;
    a.emitter = kPunctualEmitter | ls.punctual;
    a.end = light.position;
    a.endTriangle = kNoHit;
    if (light.type == kLightDirectional) {
        // From infinitely far: a medium filling all space extinguishes it, as it does the background.
        a.wi = -light.direction;
        a.distance = kFar;
        a.leadOut = 0.0f;
        a.perUnit = vec3(1.0f);
        return a;
    }
    vec3 d = light.position - from;
    float dist2 = dot(d, d);
    a.distance = sqrt(dist2);
    a.wi = d / a.distance;
    // Traced to short of the light by far more than a surface point's rounding at its
    // coordinates, or by 1e-4 of the distance (pbrt's ShadowEpsilon) where larger: a
    // light placed on a surface lights what faces it, as it would a hair's breadth in
    // front of it, instead of meeting that surface at the end.
    float offset = max(kLightOffsetPerMagnitude * maxComponent(abs(light.position)), kShadowEpsilon * a.distance);
    a.leadOut = a.distance > 0.0f ? min(offset, 0.5f * a.distance) : 0.0f;
    float falloff = light.type == kLightSpot ? spotFalloff(light, dot(light.direction, -a.wi)) : 1.0f;
    a.perUnit = vec3(dist2 > 0.0f ? falloff / dist2 : 0.0f);
    return a;
}

#endif
