// Warps from the unit square and orthonormal frames.
#ifndef VKDR_SAMPLING_GLSL
#define VKDR_SAMPLING_GLSL
#include "constants.glsl"

// Columns: tangent, bitangent, n. Branchless construction from Duff et al.,
// "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
mat3 frameFromNormal(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
    return mat3(t, bt, n);
}

// Cosine-weighted direction about +z; pdf = cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0f * kPi * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u.x)));
}

// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2.
vec2 sampleUniformTriangle(vec2 u) {
    float su = sqrt(u.x);
    return vec2(su * (1.0f - u.y), su * u.y);
}

// The power heuristic's MIS weight pdfA^2 / (pdfA^2 + pdfB^2), from the ratio of the
// smaller pdf to the larger: squaring a pdf would overflow above 1.8e19 (an emitter seen
// almost edge-on has an unbounded solid-angle pdf) and give inf / inf. Any pdf in
// [0, inf] gives a weight in [0, 1]; 0 when pdfA is 0, and a half each for equal pdfs,
// two infinite ones included.
float powerHeuristic(float pdfA, float pdfB) {
    if (!(pdfA > 0.0f)) {
        return 0.0f;
    }
    if (pdfB >= pdfA) {
        float r = pdfA < pdfB ? pdfA / pdfB : 1.0f;
        return r * r / (1.0f + r * r);
    }
    float r = pdfB / pdfA;
    return 1.0f / (1.0f + r * r);
}

// Direction with the given cosine to `axis` and azimuth 2 pi u.
vec3 directionAround(vec3 axis, float cosTheta, float u) {
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    float phi = 2.0f * kPi * u;
    return frameFromNormal(axis) * vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

#endif
