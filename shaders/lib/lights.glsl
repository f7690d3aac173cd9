// Emissive triangles as lights, chosen in proportion to their power (host-built CDF).
#ifndef VKDR_LIGHTS_GLSL
#define VKDR_LIGHTS_GLSL
#include "scene_access.glsl"
#include "sampling.glsl"

struct LightSample {
    vec3 position;
    vec3 normal;
    vec2 uv;
    uint material;
    float pdfArea;   // pmf of the triangle / its area
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
    uint light = findLight(u.x);
    uint triangle = P.lightTriangles.v[light];
    vec2 b = sampleUniformTriangle(u.yz);
    SurfacePoint sp = surfacePoint(triangle, b.x, b.y);
    return LightSample(sp.position, sp.normal, sp.uv, sp.material,
                       P.triangleInfo.v[triangle].lightPmf / sp.area);
}

// Solid-angle density of reaching a point on an emitter from `from` by light sampling.
float lightPdfSolidAngle(float pdfArea, vec3 from, vec3 lightPosition, vec3 lightNormal) {
    vec3 d = lightPosition - from;
    float dist2 = dot(d, d);
    float cosLight = abs(dot(lightNormal, d)) / sqrt(dist2);
    return cosLight > 0.0f ? pdfArea * dist2 / cosLight : 0.0f;
}

#endif
