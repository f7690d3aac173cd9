// Directions uniform in the solid angle a triangle subtends (Arvo 1995, "Stratified
// Sampling of Spherical Triangles"). Next-event estimation samples a large emitter this
// way, as Cycles and pbrt-v4 do: the density of a direction is then constant over the
// emitter instead of growing as the inverse square of the distance to its points, which
// is where area sampling leaves its noise (on walls beside a lamp).
#ifndef VKDR_SPHERICAL_TRIANGLE_GLSL
#define VKDR_SPHERICAL_TRIANGLE_GLSL
#include "constants.glsl"

// The angle between two unit vectors, from the sine and cosine together: accurate near
// 0 and pi, where acos of the dot product loses half its digits. Not from asin of the
// chord: a driver's asin may be a coarse approximation (lavapipe's put a Cornell wall's
// direct light 0.17 % low), and every error in an angle moves the solid angle with it.
float angleBetween(vec3 a, vec3 b) {
    return atan(length(cross(a, b)), dot(a, b));
}

// The unit normal of the great circle through a and b, oriented by their order.
vec3 greatCircleNormal(vec3 a, vec3 b) {
    return normalize(cross(a, b));
}

// The angles of the spherical triangle of unit vectors a, b, c at its corners, between
// the arcs that meet there.
vec3 sphericalTriangleAngles(vec3 a, vec3 b, vec3 c) {
    vec3 nAB = greatCircleNormal(a, b);
    vec3 nBC = greatCircleNormal(b, c);
    vec3 nCA = greatCircleNormal(c, a);
    return vec3(angleBetween(nAB, -nCA), angleBetween(nBC, -nAB), angleBetween(nCA, -nBC));
}

// The solid angle of the spherical triangle: its angles' excess over pi (Girard's
// theorem). The sampler below inverts the same angles, so its density is exactly one
// over this; a triangle whose corners are nearly coplanar with the viewer (a vast lamp
// seen edge-on) keeps its angles where a formula on the corners' dot products cancels.
float sphericalTriangleArea(vec3 a, vec3 b, vec3 c) {
    vec3 angles = sphericalTriangleAngles(a, b, c);
    return max(angles.x + angles.y + angles.z - kPi, 0.0f);
}

// Below this solid angle float loses the spherical triangle's angles (their sum is
// within rounding of pi), and above the other bound its edges are nearly great
// half-circles; there area sampling serves instead. A triangle that small is nearly
// uniform in solid angle when sampled by area anyway.
const float kMinSphericalSamplingArea = 1.0e-2f;
const float kMaxSphericalSamplingArea = 2.0f * kPi - 0.1f;

bool samplesBySolidAngle(float solidAngle) {
    return solidAngle >= kMinSphericalSamplingArea && solidAngle <= kMaxSphericalSamplingArea;
}

// A unit direction in the spherical triangle a, b, c (unit vectors), uniform in its
// solid angle `area` (sphericalTriangleArea) for u uniform in [0, 1)^2. u.x chooses,
// by the area it cuts off, the point c' on the arc from a to c; u.y the point on the
// arc from b to c' by the cosine of its angle from b, which is uniform in area.
vec3 sampleSphericalTriangle(vec3 corner0, vec3 corner1, vec3 corner2, float area, vec2 u) {
    // The corners in turn so that the longest arc is the one from a to c: b, whose arc
    // to c' is the second step, is then never nearly opposite a point of that arc (as a
    // corner is to the far corner of a vast lamp's half seen from under its middle).
    float d01 = dot(corner0, corner1);
    float d12 = dot(corner1, corner2);
    float d20 = dot(corner2, corner0);
    vec3 a = corner0, b = corner1, c = corner2;
    if (d01 < d20 && d01 <= d12) {
        a = corner1;
        b = corner2;
        c = corner0;
    } else if (d12 < d20) {
        a = corner2;
        b = corner0;
        c = corner1;
    }
    float alpha = angleBetween(greatCircleNormal(a, b), -greatCircleNormal(c, a));
    float cosAlpha = cos(alpha);
    float sinAlpha = sin(alpha);
    float cosC = dot(a, b);  // the arc from a to b
    // The sub-triangle a, b, c' of area u.x * area: solve for cos of the arc a c'.
    float subArea = u.x * area;
    float s = sin(subArea - alpha);
    float t = cos(subArea - alpha);
    float p = t - cosAlpha;
    float q = s + sinAlpha * cosC;
    float cosB = ((q * t - p * s) * cosAlpha - q) / ((q * s + p * t) * sinAlpha);
    cosB = clamp(cosB, -1.0f, 1.0f);
    vec3 towardC = c - dot(c, a) * a;
    vec3 cPrime = cosB * a + sqrt(max(1.0f - cosB * cosB, 0.0f)) * normalize(towardC);
    // Along the arc from b to c', uniform in area: cos of the angle from b is linear in u.y.
    float z = 1.0f - u.y * (1.0f - dot(cPrime, b));
    vec3 towardCPrime = cPrime - dot(cPrime, b) * b;
    float lengthTowardCPrime = length(towardCPrime);
    vec3 side = lengthTowardCPrime > 0.0f ? towardCPrime / lengthTowardCPrime : cPrime;
    return normalize(z * b + sqrt(max(1.0f - z * z, 0.0f)) * side);
}

#endif
