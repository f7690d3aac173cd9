// Moller-Trumbore ray/triangle test, two-sided; the host twin is
// vkdr::intersectTriangle in src/bvh/ and must stay formula-for-formula identical.
#ifndef VKDR_INTERSECT_TRIANGLE_GLSL
#define VKDR_INTERSECT_TRIANGLE_GLSL

// Returns (t, b1, b2) with t in (0, tMax), or t = -1 for a miss.
vec3 intersectTriangle(vec3 origin, vec3 direction, vec3 v0, vec3 v1, vec3 v2, float tMax) {
    const vec3 miss = vec3(-1.0f, 0.0f, 0.0f);
    vec3 e1 = v1 - v0;
    vec3 e2 = v2 - v0;
    vec3 p = cross(direction, e2);
    float det = dot(e1, p);
    if (det == 0.0f || isinf(det) || isnan(det)) {
        return miss;
    }
    float inv = 1.0f / det;
    vec3 s = origin - v0;
    float b1 = dot(s, p) * inv;
    vec3 q = cross(s, e1);
    float b2 = dot(direction, q) * inv;
    float t = dot(e2, q) * inv;
    bool inside = b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f;
    return inside && t > 0.0f && t < tMax ? vec3(t, b1, b2) : miss;
}

#endif
