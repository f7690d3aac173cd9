#pragma once
// Single scattering of a camera ray through a homogeneous medium, lit by a small
// one-sided square emitter beside the ray: the reference for the single-scattering
// render test and for the analytic gradient tests. The medium fills all space (a
// scene-wide fog) or an axis-aligned box (an enclosed medium, vacuum outside).
#include <optional>

#include <glm/glm.hpp>

#include "test_gltf.h"

namespace vkdr::test {

struct FogSetup {
    glm::dvec3 le{4.0, 3.0, 2.0};
    glm::dvec3 sigmaA{0.1, 0.05, 0.0};
    glm::dvec3 sigmaS{0.3, 0.5, 0.8};
    double g = 0.0;
    double yfov = 0.01;  // one pixel, looking along +z from the origin
    // The emitter: a square in the plane x = lightX around (lightX, 0, lightZ), facing -x.
    double lightX = 1.5, lightZ = 2.0, lightHalf = 0.25;
    struct Box {
        glm::dvec3 lo, hi;
    };
    std::optional<Box> enclosure;  // set: the medium fills this box only

    TestGltf scene() const;
};

// The pixel's radiance and its derivatives, by midpoint quadrature over the pixel's
// directions, the distance along the ray and the emitter.
struct SingleScattering {
    glm::dvec3 radiance{0.0};
    glm::dvec3 dSigmaA{0.0};  // per channel, d radiance_c / d sigma_a,c
    glm::dvec3 dSigmaS{0.0};
    glm::dvec3 dG{0.0};       // d radiance_c / d g
};
SingleScattering singleScattering(const FogSetup& fog);

}  // namespace vkdr::test
