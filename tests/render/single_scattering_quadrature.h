#pragma once
// Single scattering of a camera ray through a medium, lit by a small one-sided square
// emitter beside the ray, or by a point light: the reference for the single-scattering
// render tests and for the analytic gradient tests. The medium fills all space (a scene-wide fog) or an
// axis-aligned box (an enclosed medium, vacuum outside); an enclosed one may have a
// density that varies linearly along z, given to the renderer as a density grid.
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "test_gltf.h"
#include "volume/density_grid.h"

namespace vkdr::test {

struct FogSetup {
    glm::dvec3 le{4.0, 3.0, 2.0};
    glm::dvec3 sigmaA{0.1, 0.05, 0.0};
    glm::dvec3 sigmaS{0.3, 0.5, 0.8};
    double g = 0.0;
    // Radiance the medium emits per unit length (per unit density); singleScattering
    // leaves it out.
    glm::dvec3 emission{0.0};
    double yfov = 0.01;  // one pixel, looking along +z from the origin
    // The emitter: a square in the plane x = lightX around (lightX, 0, lightZ), facing -x.
    double lightX = 1.5, lightZ = 2.0, lightHalf = 0.25;
    // Set: a point light of this radiant intensity at (lightX, 0, lightZ) in its place.
    std::optional<glm::dvec3> pointIntensity;
    struct Box {
        glm::dvec3 lo, hi;
    };
    std::optional<Box> enclosure;  // set: the medium fills this box only
    // With an enclosure: the coefficients are sigma times density(x) = a + b x.z, from the
    // grid file `uri` beside the scene (linearDensityGrid writes it).
    struct LinearDensity {
        double a = 1.0, b = 0.0;
        std::string uri;
    };
    std::optional<LinearDensity> density;

    // With an enclosure: an albedo grid a + b x.z (RGB) scales the scattering, the rest is
    // absorbed (sigma_t unchanged); from the grid file `uri` (linearAlbedoGrid writes it).
    struct LinearAlbedo {
        glm::dvec3 a{1.0}, b{0.0};
        std::string uri;
    };
    std::optional<LinearAlbedo> albedo;

    double densityAt(glm::dvec3 x) const { return density ? density->a + density->b * x.z : 1.0; }
    glm::dvec3 albedoAt(glm::dvec3 x) const { return albedo ? albedo->a + albedo->b * x.z : glm::dvec3(1.0); }
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

// A density grid holding fog.density's a + b z at its voxel centres over the enclosure
// grown by two voxels of edge `voxel` on each side, so that the trilinear density inside
// the enclosure is exactly linear; placed in world space by its own transform.
DensityGrid linearDensityGrid(const FogSetup& fog, double voxel);

// The same for fog.albedo's a + b z, an RGB grid.
DensityGrid linearAlbedoGrid(const FogSetup& fog, double voxel);

}  // namespace vkdr::test
