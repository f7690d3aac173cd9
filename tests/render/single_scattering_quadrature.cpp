#include "single_scattering_quadrature.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vkdr::test {
namespace {

double hg(double mu, double g) {
    double d = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d));
}

double hgDLogG(double mu, double g) {
    return -2.0 * g / (1.0 - g * g) + 3.0 * (mu - g) / (1.0 + g * g - 2.0 * g * mu);
}

// The part of the segment origin + [0, tMax] * direction inside `box` (slab method), as
// [enter, leave]; empty when leave <= enter.
glm::dvec2 insideInterval(glm::dvec3 origin, glm::dvec3 direction, double tMax, const FogSetup::Box& box) {
    double enter = 0.0, leave = tMax;
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (origin[axis] < box.lo[axis] || origin[axis] > box.hi[axis]) {
                return glm::dvec2(0.0);
            }
            continue;
        }
        double t0 = (box.lo[axis] - origin[axis]) / direction[axis];
        double t1 = (box.hi[axis] - origin[axis]) / direction[axis];
        enter = std::max(enter, std::min(t0, t1));
        leave = std::min(leave, std::max(t0, t1));
    }
    return glm::dvec2(enter, std::max(enter, leave));
}

// The integral of the density over the segment's part in the medium: its length times
// the density at its middle, as the density is linear.
double densityIntegral(const FogSetup& fog, glm::dvec3 origin, glm::dvec3 direction, double tMax) {
    if (!fog.enclosure) {
        return tMax;
    }
    glm::dvec2 inside = insideInterval(origin, direction, tMax, *fog.enclosure);
    return (inside.y - inside.x) * fog.densityAt(origin + 0.5 * (inside.x + inside.y) * direction);
}

}  // namespace

TestGltf FogSetup::scene() const {
    TestGltf gltf;
    float x = float(lightX), z = float(lightZ), h = float(lightHalf);
    if (pointIntensity) {
        // A point light's colour is at most 1, its intensity the rest.
        const double strongest = std::max(std::max(pointIntensity->x, pointIntensity->y), pointIntensity->z);
        const glm::dvec3 colour = *pointIntensity / strongest;
        gltf.lights = {{{"name", "bulb"},
                        {"type", "point"},
                        {"color", {colour.x, colour.y, colour.z}},
                        {"intensity", strongest}}};
        gltf.lightNodes = {{0, glm::vec3(x, 0.0f, z)}};
    }
    // Black where the point light takes its place, so that the scene keeps its geometry.
    gltf.materials = {emissiveMaterial("lamp", pointIntensity ? glm::vec3(0.0f) : glm::vec3(le), false)};
    TestMesh lamp;
    lamp.positions = {{x, -h, z - h}, {x, h, z - h}, {x, h, z + h}, {x, -h, z + h}};
    lamp.triangles = {{0, 2, 1}, {0, 3, 2}};  // facing -x
    gltf.meshes = {lamp};
    if (enclosure) {
        gltf.materials.push_back(vkdrMediumMaterial("fog", glm::vec3(sigmaA), glm::vec3(sigmaS), float(g)));
        if (density) {
            gltf.materials.back()["extensions"]["VKDR_participating_media"]["density"] = {{"uri", density->uri}};
        }
        if (albedo) {
            gltf.materials.back()["extensions"]["VKDR_participating_media"]["albedoGrid"] = {{"uri", albedo->uri}};
        }
        if (emission != glm::dvec3(0.0)) {
            gltf.materials.back()["extensions"]["VKDR_participating_media"]["emission"] = {emission.x, emission.y,
                                                                                           emission.z};
        }
        gltf.meshes.push_back(box(glm::vec3(enclosure->lo), glm::vec3(enclosure->hi), 1));
    } else {
        gltf.extensions["VKDR_participating_media"] = {{"name", "fog"},
                                                       {"sigma_a", {sigmaA.x, sigmaA.y, sigmaA.z}},
                                                       {"sigma_s", {sigmaS.x, sigmaS.y, sigmaS.z}},
                                                       {"g", g},
                                                       {"emission", {emission.x, emission.y, emission.z}}};
    }
    gltf.yfov = float(yfov);
    return gltf;
}

SingleScattering singleScattering(const FogSetup& fog) {
    const glm::dvec3 sigmaT = fog.sigmaA + fog.sigmaS;
    constexpr int kPixelSteps = 3, kLightSteps = 24, kRaySteps = 1600;
    constexpr double kRayEnd = 80.0;
    const double tanHalf = std::tan(0.5 * fog.yfov);
    const double cell = 2.0 * fog.lightHalf / kLightSteps;
    // Where light arrives from, and its radiant intensity towards -x times the cell's area
    // (its cosine is applied per point below), or a point light's intensity.
    struct LightPoint {
        glm::dvec3 position;
        glm::dvec3 intensity;
        bool square;
    };
    std::vector<LightPoint> lightPoints;
    if (fog.pointIntensity) {
        lightPoints.push_back({glm::dvec3(fog.lightX, 0.0, fog.lightZ), *fog.pointIntensity, false});
    } else {
        for (int j = 0; j < kLightSteps * kLightSteps; ++j) {
            lightPoints.push_back({glm::dvec3(fog.lightX, -fog.lightHalf + (j % kLightSteps + 0.5) * cell,
                                              fog.lightZ - fog.lightHalf + (j / kLightSteps + 0.5) * cell),
                                   fog.le * cell * cell, true});
        }
    }
    SingleScattering out;
    for (int p = 0; p < kPixelSteps * kPixelSteps; ++p) {
        double ndcX = ((p % kPixelSteps) + 0.5) / kPixelSteps * 2.0 - 1.0;
        double ndcY = ((p / kPixelSteps) + 0.5) / kPixelSteps * 2.0 - 1.0;
        glm::dvec3 direction = glm::normalize(glm::dvec3(-ndcX * tanHalf, -ndcY * tanHalf, 1.0));
        for (int i = 0; i < kRaySteps; ++i) {
            double t = (i + 0.5) * kRayEnd / kRaySteps;
            glm::dvec3 x = t * direction;
            if (fog.enclosure && !(glm::all(glm::greaterThan(x, fog.enclosure->lo)) &&
                                   glm::all(glm::lessThan(x, fog.enclosure->hi)))) {
                continue;  // vacuum: nothing scatters here
            }
            double cameraPath = densityIntegral(fog, glm::dvec3(0.0), direction, t);
            double density = fog.densityAt(x);
            glm::dvec3 albedo = fog.albedoAt(x);
            for (const LightPoint& light : lightPoints) {
                glm::dvec3 toLight = light.position - x;
                double r = glm::length(toLight);
                double mu = glm::dot(direction, toLight / r);
                // The density's integral along the ray and towards the light: sigma_t times
                // it is the optical depth.
                double d = cameraPath + densityIntegral(fog, x, toLight / r, r);
                // Everything but sigma_s: attenuation over the ray and the light path, and
                // the density where the light scatters.
                const double cosine = light.square ? toLight.x / r : 1.0;
                glm::dvec3 base =
                    light.intensity * glm::exp(-sigmaT * d) * (density * hg(mu, fog.g) * cosine / (r * r));
                glm::dvec3 f = fog.sigmaS * albedo * base;
                out.radiance += f;
                out.dSigmaA += -d * f;
                out.dSigmaS += albedo * base * (1.0 - fog.sigmaS * d);
                out.dG += f * hgDLogG(mu, fog.g);
            }
        }
    }
    double weight = (kRayEnd / kRaySteps) / double(kPixelSteps * kPixelSteps);
    out.radiance *= weight;
    out.dSigmaA *= weight;
    out.dSigmaS *= weight;
    out.dG *= weight;
    return out;
}

namespace {

// A grid of `channels` values per voxel over the enclosure grown by two voxels of edge
// `voxel` on each side, each voxel holding value(its centre).
template <typename Value>
DensityGrid gridOverEnclosure(const FogSetup& fog, double voxel, const char* name, int channels, Value value) {
    const glm::dvec3 lo = fog.enclosure->lo - 2.0 * voxel;
    const glm::ivec3 size = glm::ivec3(glm::ceil((fog.enclosure->hi - fog.enclosure->lo) / voxel)) + 5;
    DensityGrid grid;
    grid.name = name;
    grid.size = size;
    grid.channels = channels;
    grid.indexToLocal = glm::dmat4(glm::dvec4(voxel, 0, 0, 0), glm::dvec4(0, voxel, 0, 0), glm::dvec4(0, 0, voxel, 0),
                                   glm::dvec4(lo, 1.0));
    for (int z = 0; z < size.z; ++z) {
        for (int y = 0; y < size.y; ++y) {
            for (int x = 0; x < size.x; ++x) {
                value(lo + voxel * glm::dvec3(x, y, z), grid.values);
            }
        }
    }
    return grid;
}

}  // namespace

DensityGrid linearDensityGrid(const FogSetup& fog, double voxel) {
    return gridOverEnclosure(fog, voxel, "density", 1, [&](glm::dvec3 x, std::vector<float>& values) {
        values.push_back(float(fog.densityAt(x)));
    });
}

DensityGrid linearAlbedoGrid(const FogSetup& fog, double voxel) {
    return gridOverEnclosure(fog, voxel, "color", 3, [&](glm::dvec3 x, std::vector<float>& values) {
        const glm::dvec3 albedo = fog.albedoAt(x);
        values.insert(values.end(), {float(albedo.r), float(albedo.g), float(albedo.b)});
    });
}

}  // namespace vkdr::test
