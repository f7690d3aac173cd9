// Watertight ray/triangle test (Woop, Benthin and Wald 2013, with pbrt-v4's bound on the
// distance), two-sided; the host twin is vkdr::intersectTriangle in src/bvh/ and must stay
// formula-for-formula identical. The vertices are taken relative to the ray's origin and
// sheared so that the ray runs along z: the barycentrics are then edge functions of
// coordinates of the size of the triangle's distance from the origin, and the distance a
// sum of them, so a triangle far larger than its distance (a lamp 2e10 wide, 1 away) is
// found as exactly as a small one. Moller-Trumbore's distance, a difference of products
// of the edges and the origin's offset from a vertex, lost it to rounding there.
#ifndef VKDR_INTERSECT_TRIANGLE_GLSL
#define VKDR_INTERSECT_TRIANGLE_GLSL

// a * b - c * d with one rounding (Kahan's algorithm with fused multiply-adds).
float differenceOfProducts(float a, float b, float c, float d) {
    float cd = c * d;
    return fma(a, b, -cd) + fma(-c, d, cd);
}

// n machine epsilons' worth of relative rounding, bounded (pbrt's gamma).
float roundingGamma(float n) {
    const float kUnitRoundoff = 5.9604645e-8f;  // 2^-24
    return n * kUnitRoundoff / (1.0f - n * kUnitRoundoff);
}

// Returns (t, b1, b2) with t in (0, tMax), or t = -1 for a miss.
vec3 intersectTriangle(vec3 origin, vec3 direction, vec3 v0, vec3 v1, vec3 v2, float tMax) {
    const vec3 miss = vec3(-1.0f, 0.0f, 0.0f);
    // The axes permuted so that z is the direction's largest.
    vec3 a = abs(direction);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    vec3 d = vec3(direction[kx], direction[ky], direction[kz]);
    vec3 r0 = v0 - origin, r1 = v1 - origin, r2 = v2 - origin;
    vec3 p0 = vec3(r0[kx], r0[ky], r0[kz]);
    vec3 p1 = vec3(r1[kx], r1[ky], r1[kz]);
    vec3 p2 = vec3(r2[kx], r2[ky], r2[kz]);
    float sx = -d.x / d.z, sy = -d.y / d.z, sz = 1.0f / d.z;
    p0.xy += vec2(sx, sy) * p0.z;
    p1.xy += vec2(sx, sy) * p1.z;
    p2.xy += vec2(sx, sy) * p2.z;
    float e0 = differenceOfProducts(p1.x, p2.y, p1.y, p2.x);
    float e1 = differenceOfProducts(p2.x, p0.y, p2.y, p0.x);
    float e2 = differenceOfProducts(p0.x, p1.y, p0.y, p1.x);
    if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) {
        return miss;
    }
    float det = e0 + e1 + e2;
    if (det == 0.0f || isinf(det) || isnan(det)) {
        return miss;
    }
    p0.z *= sz;
    p1.z *= sz;
    p2.z *= sz;
    float tScaled = e0 * p0.z + e1 * p1.z + e2 * p2.z;
    if (det < 0.0f ? (tScaled >= 0.0f || tScaled < tMax * det) : (tScaled <= 0.0f || tScaled > tMax * det)) {
        return miss;
    }
    float invDet = 1.0f / det;
    float t = tScaled * invDet;
    // A distance within its own rounding of 0 is not a hit in front of the origin.
    float maxZ = max(max(abs(p0.z), abs(p1.z)), abs(p2.z));
    float maxX = max(max(abs(p0.x), abs(p1.x)), abs(p2.x));
    float maxY = max(max(abs(p0.y), abs(p1.y)), abs(p2.y));
    float deltaZ = roundingGamma(3.0f) * maxZ;
    float deltaX = roundingGamma(5.0f) * (maxX + maxZ);
    float deltaY = roundingGamma(5.0f) * (maxY + maxZ);
    float deltaE = 2.0f * (roundingGamma(2.0f) * maxX * maxY + deltaY * maxX + deltaX * maxY);
    float maxE = max(max(abs(e0), abs(e1)), abs(e2));
    float deltaT = 3.0f * (roundingGamma(3.0f) * maxE * maxZ + deltaE * maxZ + deltaZ * maxE) * abs(invDet);
    if (!(t > deltaT) || !(t < tMax)) {
        return miss;
    }
    return vec3(t, e1 * invDet, e2 * invDet);
}

#endif
