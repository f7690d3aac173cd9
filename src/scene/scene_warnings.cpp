#include "scene/scene_warnings.h"

#include <glm/glm.hpp>

#include "core/printable_text.h"
#include "scene/camera_on_boundary.h"

namespace vkdr {
namespace {

// In double, as the renderer's light distribution measures it: a triangle of zero area
// there is never sampled as a light.
bool hasZeroArea(const Scene& scene, const glm::uvec3& triangle) {
    glm::dvec3 e1 = glm::dvec3(scene.positions[triangle[1]] - scene.positions[triangle[0]]);
    glm::dvec3 e2 = glm::dvec3(scene.positions[triangle[2]] - scene.positions[triangle[0]]);
    return glm::length(glm::cross(e1, e2)) == 0.0;
}

// Whether light from infinitely far (the background, a directional light) reaches the
// scene: a homogeneous scene medium extinguishes it in every channel where it has
// extinction, while a grid's density is 0 outside the grid.
bool reachesFromInfinity(const Scene& scene, glm::vec3 radiance) {
    glm::vec3 sigmaT(0.0f);
    if (scene.sceneMedium != kNoMedium && !scene.media[size_t(scene.sceneMedium)].isHeterogeneous()) {
        const Medium& medium = scene.media[size_t(scene.sceneMedium)];
        sigmaT = medium.sigma_a + medium.sigma_s;
    }
    for (int c = 0; c < 3; ++c) {
        if (radiance[c] > 0.0f && sigmaT[c] == 0.0f) return true;
    }
    return false;
}

// A grid of no active voxels is 0 everywhere: likely the wrong grid or an unfinished
// simulation's cache, and not a parameter (it has no values).
std::vector<std::string> emptyGridWarnings(const Scene& scene) {
    struct Role {
        int32_t Medium::*grid;
        const char* kind;
        const char* consequence;
    };
    constexpr Role kRoles[] = {{&Medium::densityGrid, "density", "the medium is empty"},
                               {&Medium::emissionGrid, "emission", "the medium emits nothing"},
                               {&Medium::albedoGrid, "albedo", "the medium's albedo is 0 (it scatters nothing)"}};
    std::vector<std::string> warnings;
    for (const Medium& medium : scene.media) {
        for (const Role& role : kRoles) {
            const int32_t grid = medium.*role.grid;
            if (grid < 0 || scene.densityGrids[size_t(grid)].grid.voxelCount() > 0) continue;
            const SceneDensityGrid& placed = scene.densityGrids[size_t(grid)];
            warnings.push_back("medium '" + medium.name + "': its " + role.kind + " grid '" + placed.grid.name +
                               "' in " + placed.file.filename().string() + " has no active voxels, so " +
                               role.consequence);
        }
    }
    return warnings;
}

}  // namespace

std::vector<std::string> sceneWarnings(const Scene& scene, const std::filesystem::path& file) {
    std::vector<size_t> zeroAreaEmitters(scene.materials.size(), 0);
    size_t emittingTriangles = 0;
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const uint32_t material = scene.triangleMaterial[t];
        if (!scene.materials[material].isEmissive()) {
            continue;
        }
        if (hasZeroArea(scene, scene.triangles[t])) {
            ++zeroAreaEmitters[material];
        } else {
            ++emittingTriangles;
        }
    }
    std::vector<std::string> warnings;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        if (zeroAreaEmitters[m] > 0) {
            warnings.push_back(std::to_string(zeroAreaEmitters[m]) + " emissive triangle" +
                               (zeroAreaEmitters[m] == 1 ? "" : "s") + " of material '" + scene.materials[m].name +
                               "' ha" + (zeroAreaEmitters[m] == 1 ? "s" : "ve") +
                               " zero area (degenerate) and emit nothing");
        }
    }
    std::vector<bool> placed(scene.punctualLights.size(), false);
    size_t shiningLights = 0;
    bool extinguishedSun = false;  // a placed directional light above 0 that the scene medium extinguishes
    for (const LightPlacement& placement : scene.lightPlacements) {
        placed[placement.light] = true;
        const PunctualLight& light = scene.punctualLights[placement.light];
        const bool reaches = light.type == PunctualLight::Type::Directional
                                 ? reachesFromInfinity(scene, light.intensity)
                                 : light.intensity != glm::vec3(0.0f);
        shiningLights += reaches ? 1 : 0;
        extinguishedSun = extinguishedSun || (!reaches && light.intensity != glm::vec3(0.0f));
    }
    for (size_t i = 0; i < placed.size(); ++i) {
        if (!placed[i]) {
            warnings.push_back("light '" + scene.punctualLights[i].name + "' is placed by no node and lights nothing");
        }
    }
    if (emittingTriangles == 0 && shiningLights == 0 && !scene.anyMediumEmits() &&
        !reachesFromInfinity(scene, scene.background)) {
        // Set where anything is extinguished: only a scene medium extinguishes.
        const std::string extinguishing =
            scene.sceneMedium == kNoMedium ? "" : "the scene medium '" + scene.media[size_t(scene.sceneMedium)].name +
                                                      "'";
        warnings.push_back(
            "the scene has no light: no triangle of non-zero area has an emissive material, " +
            (extinguishedSun
                 ? "every punctual light has intensity 0 or is a directional light that " + extinguishing +
                       " extinguishes"
                 : "no punctual light has an intensity above 0") +
            ", no medium emits and the background is " +
            (scene.background == glm::vec3(0.0f) ? "black" : "extinguished by " + extinguishing) +
            ", so the image will be black");
    }
    for (std::string& warning : emptyGridWarnings(scene)) warnings.push_back(std::move(warning));
    for (std::string& warning : camerasOnMediumBoundaries(scene)) warnings.push_back(std::move(warning));
    // Names from the file may hold control characters, as in the loader's warnings.
    for (std::string& warning : warnings) warning = printableText(file.string() + ": " + warning);
    return warnings;
}

}  // namespace vkdr
