#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/source_files.h"

#include "volume/density_grid.h"

namespace vkdr {

// Index meaning "no medium" (vacuum) wherever a medium index is stored.
inline constexpr int32_t kNoMedium = -1;

struct Camera {
    std::string name;
    glm::mat4 cameraToWorld{1.0f};  // glTF convention: looks down -Z, +Y up
    float yfov = 0.8f;              // radians, vertical field of view (perspective)
    float aspectRatio = 0.0f;       // width / height; 0 when the file does not say
    // > 0: an orthographic camera, whose rays start on its XY plane and run parallel down
    // -Z through a view of this half height (glTF's ymag, in world units); yfov unused.
    float orthographicHalfHeight = 0.0f;
    bool orthographic() const { return orthographicHalfHeight > 0.0f; }
};

// Linear RGBA texels (sRGB-encoded images are decoded on load), row 0 = the image's
// top row, which is glTF's v = 0.
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> texels;
};

// What a texture is looked up with outside [0, 1]: glTF's sampler wrap modes.
enum class TextureWrap : uint32_t { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };

// How a material looks up one of its textures: the texture coordinates are transformed
// (KHR_texture_transform: (u', v') = (dot(uRow, (u, v, 1)), dot(vRow, (u, v, 1)))), then
// wrapped along each axis by the texture's sampler.
struct TextureMapping {
    glm::vec3 uRow{1.0f, 0.0f, 0.0f};
    glm::vec3 vRow{0.0f, 1.0f, 0.0f};
    TextureWrap wrapS = TextureWrap::Repeat;  // along u
    TextureWrap wrapT = TextureWrap::Repeat;  // along v
};

struct Material {
    std::string name;                     // glTF name, or its index as text when unnamed
    glm::vec3 baseColor{1.0f};            // Lambertian albedo factor (linear RGB)
    int32_t baseColorTexture = -1;        // index into Scene::textures, multiplies baseColor
    TextureMapping baseColorMapping;
    glm::vec3 emission{0.0f};             // emitted radiance: emissiveFactor * emissive_strength
    int32_t emissionTexture = -1;         // index into Scene::textures, multiplies emission
    TextureMapping emissionMapping;
    bool doubleSided = false;             // emits from both sides when true, else the front only
    // Emits in the file as loaded: its emission is the parameter lights/<name>/emission,
    // whatever value that is later set to (0 included), so the names stay the same.
    bool emitter = false;
    int32_t interiorMedium = kNoMedium;   // >= 0: a pass-through boundary enclosing media[i]
    bool isMediumBoundary() const { return interiorMedium != kNoMedium; }
    bool isEmissive() const { return emission != glm::vec3(0.0f); }
};

// A participating medium; sigma in inverse scene units. Homogeneous, or a density grid
// medium whose coefficients at a point are sigma_a, sigma_s and emission times the grid's
// value there. An emission grid (a flame or temperature-like strength) takes the place of
// the density in the emission: j(x) = emission * strength(x), in either kind of medium.
// An albedo grid a(x) (RGB, in [0, 1]) scales the scattering and turns the rest into
// absorption, keeping the extinction: sigma_s(x) = a(x) sigma_s d(x) and sigma_a(x) =
// (sigma_a + (1 - a(x)) sigma_s) d(x).
struct Medium {
    std::string name;  // parameter prefix is "media/<name>/"
    glm::vec3 sigma_a{0.0f};
    glm::vec3 sigma_s{0.0f};
    float g = 0.0f;    // Henyey-Greenstein anisotropy, in [-0.99, 0.99] (scene/parameter_kinds.h)
    // Radiance emitted per unit length, in every direction alike (a source term of the
    // radiative transfer equation, as Cycles' volume emission).
    glm::vec3 emission{0.0f};
    int32_t densityGrid = -1;   // index into Scene::densityGrids; -1: homogeneous
    int32_t emissionGrid = -1;  // index into Scene::densityGrids; -1: none
    int32_t albedoGrid = -1;    // index into Scene::densityGrids (an RGB grid); -1: none
    bool isHeterogeneous() const { return densityGrid >= 0; }
    // As the stages' equiangular sampling asks (shaders/lib/distance_mis.glsl).
    bool scattersHomogeneously() const { return densityGrid < 0 && albedoGrid < 0 && sigma_s != glm::vec3(0.0f); }
    bool hasEmissionGrid() const { return emissionGrid >= 0; }
    bool hasAlbedoGrid() const { return albedoGrid >= 0; }
    bool isEmissive() const { return emission != glm::vec3(0.0f); }
};

// A grid as the scene places it: a medium's density, emission strength or albedo.
struct SceneDensityGrid {
    std::filesystem::path file;     // the file it was read from
    DensityGrid grid;
    glm::dmat4 indexToWorld{1.0};   // the node's transform times the grid's own index-to-local one
};

// A KHR_lights_punctual light as the file defines it. `intensity` is the glTF light's
// color x intensity: radiant intensity per steradian (point, spot) or irradiance
// (directional), in the units of an emitter's radiance. One definition may be placed by
// several nodes; its parameter sets them all.
struct PunctualLight {
    enum class Type { Point, Spot, Directional };
    std::string name;            // parameter prefix is "lights/<name>/"
    Type type = Type::Point;
    glm::vec3 intensity{1.0f};
    float cosInnerCone = 1.0f;   // spot: full intensity within the inner cone,
    float cosOuterCone = 0.0f;   // none outside the outer one
};

// Where a node puts a punctual light, in world space.
struct LightPlacement {
    uint32_t light = 0;                      // index into Scene::punctualLights
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, where the light shines: its node's -Z
};

// A flattened scene: every mesh instance baked into world space.
struct Scene {
    std::vector<glm::vec3> positions;           // world space, per vertex
    // Per vertex, from the TEXCOORD set its material's textures name ((0, 0) when absent).
    std::vector<glm::vec2> uvs;
    // COLOR_0's RGB per vertex, multiplying the base colour (white where a primitive has
    // none); empty when no primitive has one.
    std::vector<glm::vec3> colors;
    // Shading normals per vertex, unit, in world space: the NORMAL attribute where a mesh
    // has one, else (0, 0, 0), which means the triangle's own normal.
    std::vector<glm::vec3> normals;
    std::vector<glm::uvec3> triangles;          // vertex indices, counter-clockwise = front
    std::vector<uint32_t> triangleMaterial;     // per triangle, index into materials
    // Per triangle: the medium on the front (outward) side of a boundary triangle,
    // where a ray goes when it leaves the enclosed medium: the scene medium, or the
    // enclosing medium for nested boundaries. kNoMedium for non-boundary triangles and
    // for boundaries whose outside is vacuum. Boundary meshes are closed and their
    // triangles wound so the geometric normal points out of the enclosed medium.
    std::vector<int32_t> triangleOutsideMedium;
    std::vector<Material> materials;
    std::vector<Medium> media;
    std::vector<SceneDensityGrid> densityGrids;  // densities, emission strengths and albedos
    std::vector<Texture> textures;
    std::vector<Camera> cameras;
    std::vector<PunctualLight> punctualLights;  // in the file's order
    std::vector<LightPlacement> lightPlacements;
    int32_t sceneMedium = kNoMedium;            // fills all space outside enclosed media
    glm::vec3 background{0.0f};                 // radiance of rays that escape the scene
    // The glTF file and the buffers and images it read, as loaded: writing the scene back
    // (scene/write_scene.h) refuses one that has changed since.
    std::vector<SourceFile> sourceFiles;

    bool anyMediumEmits() const { return anyMedium(&Medium::isEmissive); }

    bool anyMedium(bool (Medium::*property)() const) const {
        for (const Medium& medium : media) {
            if ((medium.*property)()) return true;
        }
        return false;
    }
};

}  // namespace vkdr
