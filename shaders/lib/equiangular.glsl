// Equiangular distance sampling (Kulla and Fajardo 2012, "Importance Sampling Techniques
// for Path Tracing in Participating Media"): a distance t along a ray segment [0, tMax)
// with density proportional to 1 / |x(t) - y|^2, the inverse square distance to a point
// y on a light. Uniform in the angle that x(t) subtends at y, it cancels the 1 / r^2 of
// a light's geometry term, where distance sampling leaves fireflies near the light.
#ifndef VKDR_EQUIANGULAR_GLSL
#define VKDR_EQUIANGULAR_GLSL
#include "constants.glsl"

// The segment as seen from y: `closest` is the t of the ray's point nearest to y,
// `height` the distance from y to the ray's line, and [angleNear, angleFar] the angles
// (from the perpendicular) of the segment's ends. Sampling is refused (`valid` false)
// where y lies on the ray's line or the segment subtends no angle: the density is then
// zero everywhere, in the sampler and in every weight that asks for it alike.
struct EquiangularSegment {
    float end;  // tMax
    float closest;
    float height;
    float angleNear;
    float angleFar;
    bool valid;
};

EquiangularSegment equiangularSegment(vec3 origin, vec3 direction, float tMax, vec3 lightPoint) {
    EquiangularSegment s;
    s.end = tMax;
    vec3 toLight = lightPoint - origin;
    s.closest = dot(toLight, direction);
    s.height = length(toLight - s.closest * direction);
    s.angleNear = atan(-s.closest, s.height);
    s.angleFar = atan(tMax - s.closest, s.height);
    // The relative bound keeps tan() and the density finite in single precision.
    s.valid = s.height > 1e-6f * max(abs(s.closest), 1e-3f) && s.angleFar - s.angleNear > 1e-6f;
    return s;
}

// Density of t in [0, tMax): 0 outside it, and everywhere where the segment is not valid.
float equiangularPdf(EquiangularSegment s, float t) {
    if (!s.valid || t < 0.0f || t >= s.end) {
        return 0.0f;
    }
    float along = t - s.closest;
    return s.height / ((s.angleFar - s.angleNear) * (s.height * s.height + along * along));
}

// The distance at u in [0, 1): uniform in angle between the segment's ends.
float sampleEquiangular(EquiangularSegment s, float u) {
    float angle = mix(s.angleNear, s.angleFar, u);
    return max(s.closest + s.height * tan(angle), 0.0f);
}

#endif
