// The lights of next-event estimation: emissive triangles and punctual lights (point,
// spot, directional), chosen in proportion to their power (host-built CDF). A triangle
// seen from the vertex under a large enough solid angle is sampled uniformly in that
// solid angle, others uniformly in area.
#ifndef VKDR_LIGHTS_GLSL
#define VKDR_LIGHTS_GLSL
#include "scene_access.glsl"
#include "sampling.glsl"
#include "spherical_triangle.glsl"

const uint kNoPunctualLight = 0xffffffffu;

struct LightSample {
    vec3 position;   // on the emitter, or the punctual light's position
    vec3 normal;     // the emitter's geometric normal
    vec2 uv;
    uint material;   // the emitter's material
    float pdfArea;   // pmf of the triangle / its area; a punctual light's pmf
    float pdfSolidAngle;  // pmf of the triangle / its solid angle where sampled in it, else 0
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

LightSample punctualLightSample(uint index) {
    GpuPunctualLight light = P.punctualLights.v[index];
    return LightSample(light.position, vec3(0.0f), vec2(0.0f), 0u, light.pmf, 0.0f, index, kNoHit);
}

// The point at barycentrics b of the emitter triangle `triangle`, with the density of
// sampling it uniformly in area.
LightSample emitterPoint(uint triangle, vec2 b) {
    SurfacePoint sp = surfacePoint(triangle, b.x, b.y);
    return LightSample(sp.position, sp.normal, sp.uv, sp.material,
                       P.triangleInfo.v[triangle].lightPmf / sp.area, 0.0f, kNoPunctualLight, triangle);
}

// A triangle's corners, and the directions from `from` to them.
struct TriangleView {
    vec3 v0;
    vec3 v1;
    vec3 v2;
    vec3 a;
    vec3 b;
    vec3 c;
    float solidAngle;
};

TriangleView triangleView(uint triangle, vec3 from) {
    TriangleView view;
    view.v0 = P.triangleVertices.v[3u * triangle].xyz;
    view.v1 = P.triangleVertices.v[3u * triangle + 1u].xyz;
    view.v2 = P.triangleVertices.v[3u * triangle + 2u].xyz;
    view.a = normalize(view.v0 - from);
    view.b = normalize(view.v1 - from);
    view.c = normalize(view.v2 - from);
    view.solidAngle = sphericalTriangleArea(view.a, view.b, view.c);
    return view;
}

// The barycentrics (b1, b2) where the ray from `from` along `direction` meets the plane
// of the triangle, clamped into it (a direction sampled in the triangle's solid angle
// meets it up to rounding at its edges).
vec2 planeBarycentrics(TriangleView view, vec3 from, vec3 direction) {
    vec3 e1 = view.v1 - view.v0;
    vec3 e2 = view.v2 - view.v0;
    vec3 pv = cross(direction, e2);
    float det = dot(e1, pv);
    vec3 s = from - view.v0;
    vec3 qv = cross(s, e1);
    float b1 = clamp(dot(s, pv) / det, 0.0f, 1.0f);
    float b2 = clamp(dot(direction, qv) / det, 0.0f, 1.0f);
    float sum = b1 + b2;
    return sum > 1.0f ? vec2(b1, b2) / sum : vec2(b1, b2);
}

// A light chosen by u.x, and on a triangle a point by u.yz: when `inSolidAngle` and
// `from` sees the triangle under a solid angle that float resolves (samplesBySolidAngle),
// where a direction uniform in that solid angle meets it; elsewhere uniform in its area.
LightSample sampleLightSource(vec3 u, bool inSolidAngle, vec3 from) {
    uint source = P.lightSources.v[findLight(u.x)];
    if ((source & kPunctualEmitter) != 0u) {
        return punctualLightSample(source & ~kPunctualEmitter);
    }
    bool unlit = false;
    if (inSolidAngle) {
        TriangleView view = triangleView(source, from);
        if (samplesBySolidAngle(view.solidAngle)) {
            vec3 direction = sampleSphericalTriangle(view.a, view.b, view.c, view.solidAngle, u.yz);
            if (dot(direction, direction) < 2.0f) {
                LightSample ls = emitterPoint(source, planeBarycentrics(view, from, direction));
                ls.pdfSolidAngle = P.triangleInfo.v[source].lightPmf / view.solidAngle;
                return ls;
            }
            // Not a number from a triangle at the edge of float's reach: a sample of
            // density 0, which lights nothing, rather than a non-finite contribution.
            unlit = true;
        }
    }
    LightSample ls = emitterPoint(source, sampleUniformTriangle(u.yz));
    if (unlit) {
        ls.pdfArea = 0.0f;
    }
    return ls;
}

// A light chosen by u.x; a triangle's point by u.yz uniformly in its area.
LightSample sampleLightPoint(vec3 u) {
    return sampleLightSource(u, false, vec3(0.0f));
}

// The light sample of next-event estimation at the vertex `from`.
LightSample sampleLight(vec3 u, vec3 from) {
    return sampleLightSource(u, true, from);
}

// Solid-angle density of reaching a point on an emitter from `from` by sampling the
// emitter's area with density pdfArea.
float lightPdfSolidAngle(float pdfArea, vec3 from, vec3 lightPosition, vec3 lightNormal) {
    vec3 d = lightPosition - from;
    float dist2 = dot(d, d);
    float cosLight = abs(dot(lightNormal, d)) / sqrt(dist2);
    return cosLight > 0.0f ? pdfArea * dist2 / cosLight : 0.0f;
}

// Solid-angle density with which next-event estimation at `from` (sampleLight) finds
// the point `lightPosition` on the emitter triangle `triangle`, whose density in area
// sampling is pdfArea.
float nextEventPdf(uint triangle, float pdfArea, vec3 from, vec3 lightPosition, vec3 lightNormal) {
    float solidAngle = triangleView(triangle, from).solidAngle;
    if (samplesBySolidAngle(solidAngle)) {
        return P.triangleInfo.v[triangle].lightPmf / solidAngle;
    }
    return lightPdfSolidAngle(pdfArea, from, lightPosition, lightNormal);
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
// `misPdf` is next-event estimation's density at the point lit (sampleLight): the pdf
// where the sample came from it, and what MIS weighs any other sample by, so that the
// weights of all strategies sum to one. `areaPdf` is the density, in the same solid
// angle, of the same light point sampled uniformly in area (sampleLightPoint), as the
// equiangular next event samples it (distance_mis.glsl).
struct LightArrival {
    vec3 wi;
    float distance;
    vec3 perUnit;
    vec3 parameter;
    float pdf;
    float misPdf;
    float areaPdf;
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
    return (light.isDelta ? 1.0f : powerHeuristic(light.misPdf, scatterPdf)) / light.pdf;
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
        a.areaPdf = lightPdfSolidAngle(ls.pdfArea, from, ls.position, ls.normal);
        a.pdf = ls.pdfSolidAngle > 0.0f ? ls.pdfSolidAngle : a.areaPdf;
        a.misPdf = a.pdf;
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
    a.misPdf = a.pdf;
    a.areaPdf = a.pdf;
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
