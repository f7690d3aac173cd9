#include "render/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.h"
#include "core/format_text.h"
#include "device_types.h"
#include "render/light_distribution.h"
#include "vk/context.h"

namespace vkdr {
namespace {

float sceneExtent(const Scene& scene) {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : scene.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return std::max(glm::length(hi - lo), 1.0e-3f);
}

uint32_t mediumIndex(int32_t medium) {
    return medium < 0 ? gpu::kNoMediumIndex : static_cast<uint32_t>(medium);
}

// A value below float's least normal number as 0, which the device is sent: devices may
// flush such subnormal numbers to 0 in one operation and not in the next (lavapipe does),
// which made a sigma_s or base colour of 1e-40 give NaN gradients. At 0 a factor's
// gradient comes from the derivative mode (docs/gradients.md), as it should.
float withoutSubnormal(float value) {
    return std::fpclassify(value) == FP_SUBNORMAL ? 0.0f : value;
}

glm::vec3 withoutSubnormals(glm::vec3 value) {
    return {withoutSubnormal(value.x), withoutSubnormal(value.y), withoutSubnormal(value.z)};
}

glm::vec4 withoutSubnormals(glm::vec4 value) {
    return glm::vec4(withoutSubnormals(glm::vec3(value)), withoutSubnormal(value.w));
}

std::vector<gpu::GpuMaterial> deviceMaterials(const Scene& scene) {
    std::vector<gpu::GpuMaterial> out;
    for (const Material& m : scene.materials) {
        const TextureMapping& base = m.baseColorMapping;
        const TextureMapping& emission = m.emissionMapping;
        out.push_back({glm::vec4(withoutSubnormals(m.baseColor), 0.0f),
                       glm::vec4(withoutSubnormals(m.emission), 0.0f),
                       m.baseColorTexture,
                       m.emissionTexture,
                       m.interiorMedium,
                       m.doubleSided ? 1u : 0u,
                       {glm::vec4(base.uRow, 0.0f), glm::vec4(base.vRow, 0.0f)},
                       {glm::vec4(emission.uRow, 0.0f), glm::vec4(emission.vRow, 0.0f)},
                       glm::uvec4(uint32_t(base.wrapS), uint32_t(base.wrapT), uint32_t(emission.wrapS),
                                  uint32_t(emission.wrapT))});
    }
    return out;
}

// A density grid's medium tracks sigma_a + sigma_s times the density: where that sum is
// beyond float range, a voxel of density 0 gives infinity times 0 and the image NaN.
// (Where the sum fits but the density's product does not, tracking counts too many steps
// and the renderer refuses the medium as too dense.)
void requireExtinctionInFloatRange(const Medium& medium) {
    for (int c = 0; c < 3; ++c) {
        if (double(medium.sigma_a[c]) + double(medium.sigma_s[c]) > double(std::numeric_limits<float>::max())) {
            throw UnrenderableValuesError("the density grid medium '" + medium.name +
                                          "' is too dense to render: its sigma_a + sigma_s (" +
                                          formatText("%g + %g", double(medium.sigma_a[c]), double(medium.sigma_s[c])) +
                                          ", channel " + "RGB"[c] + ") is beyond float range; lower them");
        }
    }
}

std::vector<gpu::GpuMedium> deviceMedia(const Scene& scene) {
    std::vector<gpu::GpuMedium> out;
    for (const Medium& m : scene.media) {
        if (m.isHeterogeneous()) requireExtinctionInFloatRange(m);
        out.push_back({withoutSubnormals(m.sigma_a), withoutSubnormal(m.g), withoutSubnormals(m.sigma_s),
                       m.isHeterogeneous() ? uint32_t(m.densityGrid) : gpu::kNoDensityGrid,
                       withoutSubnormals(m.emission), m.hasEmissionGrid() ? uint32_t(m.emissionGrid) : gpu::kNoDensityGrid,
                       m.hasAlbedoGrid() ? uint32_t(m.albedoGrid) : gpu::kNoDensityGrid, {0u, 0u, 0u}});
    }
    return out;
}

// The placed punctual lights with their lights' values and `placementPmf`.
std::vector<gpu::GpuPunctualLight> devicePunctualLights(const Scene& scene, std::span<const float> placementPmf) {
    std::vector<gpu::GpuPunctualLight> out;
    for (size_t i = 0; i < scene.lightPlacements.size(); ++i) {
        const LightPlacement& placement = scene.lightPlacements[i];
        const PunctualLight& light = scene.punctualLights[placement.light];
        const uint32_t type = light.type == PunctualLight::Type::Point  ? gpu::kLightPoint
                              : light.type == PunctualLight::Type::Spot ? gpu::kLightSpot
                                                                        : gpu::kLightDirectional;
        out.push_back({placement.position, type, placement.direction, light.cosOuterCone,
                       withoutSubnormals(light.intensity),
                       light.cosInnerCone, placement.light, placementPmf[i], 0u, 0u});
    }
    return out;
}

// What the emitter distribution depends on (GpuScene::emitterPowers).
std::vector<glm::vec3> emitterPowers(const Scene& scene) {
    std::vector<glm::vec3> powers = meanEmittedRadiance(scene);
    for (const PunctualLight& light : scene.punctualLights) {
        powers.push_back(light.intensity);
    }
    return powers;
}

// Every texture's texels, one texture after another.
std::vector<glm::vec4> allTexels(const Scene& scene) {
    std::vector<glm::vec4> texels;
    for (const Texture& tex : scene.textures) {
        for (const glm::vec4& texel : tex.texels) texels.push_back(withoutSubnormals(texel));
    }
    return texels;
}

}  // namespace

GpuScene uploadScene(const VulkanContext& context, const Scene& scene, const Bvh& bvh) {
    const size_t count = bvh.triangleOrder.size();
    std::vector<glm::vec4> vertices(3 * count);
    std::vector<glm::vec4> uvs(2 * count, glm::vec4(0.0f));
    std::vector<glm::vec4> normals(3 * count, glm::vec4(0.0f));
    const bool hasNormals = scene.normals.size() == scene.positions.size();
    // Without vertex colours no triangle reads them (GpuTriangleInfo::vertexColors).
    const bool hasColors = !scene.colors.empty();
    std::vector<glm::vec4> colors(hasColors ? 3 * count : 1, glm::vec4(1.0f));
    for (size_t i = 0; i < count; ++i) {
        const glm::uvec3& tri = scene.triangles[bvh.triangleOrder[i]];
        for (int k = 0; k < 3; ++k) {
            vertices[3 * i + k] = glm::vec4(scene.positions[tri[k]], 0.0f);
            if (hasNormals) {
                normals[3 * i + k] = glm::vec4(scene.normals[tri[k]], 0.0f);
            }
            if (hasColors) {
                colors[3 * i + k] = glm::vec4(scene.colors[tri[k]], 1.0f);
            }
        }
        if (!scene.uvs.empty()) {
            uvs[2 * i] = glm::vec4(scene.uvs[tri[0]], scene.uvs[tri[1]]);
            uvs[2 * i + 1] = glm::vec4(scene.uvs[tri[2]], 0.0f, 0.0f);
        }
    }
    std::vector<gpu::GpuTexture> textures;
    uint32_t firstTexel = 0;
    for (const Texture& tex : scene.textures) {
        textures.push_back({firstTexel, static_cast<uint32_t>(tex.width), static_cast<uint32_t>(tex.height), 0u});
        firstTexel += static_cast<uint32_t>(tex.texels.size());
    }

    GpuScene gpu;
    gpu.triangleVertices = uploadVector<glm::vec4>(context, vertices, "triangle vertices");
    gpu.triangleUvs = uploadVector<glm::vec4>(context, uvs, "triangle uvs");
    gpu.triangleNormals = uploadVector<glm::vec4>(context, normals, "triangle normals");
    gpu.triangleColors = uploadVector<glm::vec4>(context, colors, "triangle colours");
    gpu.bvhNodes = uploadVector<BvhNode>(context, bvh.nodes, "bvh nodes");
    gpu.textures = uploadVector<gpu::GpuTexture>(context, textures, "textures");
    gpu.extent = sceneExtent(scene);
    gpu.sceneMedium = mediumIndex(scene.sceneMedium);
    uploadSceneParameters(context, scene, bvh.triangleOrder, gpu);
    return gpu;
}

void uploadSceneParameters(const VulkanContext& context, const Scene& scene, std::span<const uint32_t> triangleOrder,
                           GpuScene& gpu) {
    const std::vector<gpu::GpuMaterial> materials = deviceMaterials(scene);
    const std::vector<gpu::GpuMedium> media = deviceMedia(scene);
    overwriteBuffer(context, gpu.materials, std::as_bytes(std::span(materials)), "materials");
    overwriteBuffer(context, gpu.media, std::as_bytes(std::span(media)), "media");
    std::vector<glm::vec4> texels = allTexels(scene);
    overwriteBuffer(context, gpu.texels, std::as_bytes(std::span(texels)), "texels");
    writeDensityGrids(context, scene, gpu.densityGrids);

    std::vector<glm::vec3> powers = emitterPowers(scene);
    if (gpu.emitterPowers && powers == *gpu.emitterPowers) {
        return;
    }
    std::vector<glm::vec3> emitted = meanEmittedRadiance(scene);
    LightDistribution lights = buildLightDistribution(scene, emitted, 0.5 * double(gpu.extent));
    std::vector<gpu::GpuTriangleInfo> info(triangleOrder.size());
    std::vector<uint32_t> bvhPosition(scene.triangles.size());
    for (size_t i = 0; i < triangleOrder.size(); ++i) {
        uint32_t t = triangleOrder[i];
        bvhPosition[t] = static_cast<uint32_t>(i);
        info[i] = {scene.triangleMaterial[t], mediumIndex(scene.triangleOutsideMedium[t]), lights.trianglePmf[t],
                   scene.colors.empty() ? 0u : 1u};
    }
    std::vector<uint32_t> sources;
    for (uint32_t source : lights.sources) {
        sources.push_back((source & gpu::kPunctualEmitter) ? source : bvhPosition[source]);
    }
    const std::vector<gpu::GpuPunctualLight> punctual = devicePunctualLights(scene, lights.placementPmf);
    overwriteBuffer(context, gpu.triangleInfo, std::as_bytes(std::span(info)), "triangle info");
    overwriteBuffer(context, gpu.lightSources, std::as_bytes(std::span(sources)), "light sources");
    overwriteBuffer(context, gpu.lightCdf, std::as_bytes(std::span(lights.cdf)), "light cdf");
    overwriteBuffer(context, gpu.punctualLights, std::as_bytes(std::span(punctual)), "punctual lights");
    gpu.lightCount = static_cast<uint32_t>(sources.size());
    gpu.emitterPowers = std::move(powers);
}

}  // namespace vkdr
