#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "device_types.h"
#include "render/gpu_density_grids.h"
#include "scene/scene.h"
#include "vk/buffer.h"

namespace vkdr {

class VulkanContext;

// The scene as the stages read it: triangles and their attributes in BVH leaf order,
// the BVH, materials, media and their density grids, textures, the punctual lights and
// the emitter CDF.
struct GpuScene {
    Buffer triangleVertices;
    Buffer triangleUvs;
    Buffer triangleNormals;
    Buffer triangleColors;
    Buffer triangleInfo;
    Buffer bvhNodes;
    Buffer materials;
    Buffer media;
    Buffer textures;
    Buffer texels;
    Buffer lightSources;
    Buffer lightCdf;
    Buffer punctualLights;
    GpuDensityGrids densityGrids;
    uint32_t lightCount = 0;
    uint32_t sceneMedium = gpu::kNoMediumIndex;  // the medium outside every boundary
    float extent = 0.0f;  // the diagonal of the scene's bounding box (at least 1e-3), scene units
    // Each material's mean emitted radiance, then each punctual light's intensity, when
    // the emitter distribution was built.
    std::optional<std::vector<glm::vec3>> emitterPowers;
};

GpuScene uploadScene(const VulkanContext& context, const Scene& scene, const Bvh& bvh);

// Uploads what the differentiable parameters change, for new parameter values of the
// same scene (geometry, material assignment and sidedness as before): materials, media,
// texels and density grids (with their majorants), written in place, and the emitter distribution (per triangle, as large
// as the geometry) and punctual lights only when a material's mean emitted radiance or
// a light's intensity changed.
void uploadSceneParameters(const VulkanContext& context, const Scene& scene, std::span<const uint32_t> triangleOrder,
                           GpuScene& gpu);

}  // namespace vkdr
