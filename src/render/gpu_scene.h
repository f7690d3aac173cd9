#pragma once
#include <cstdint>
#include <span>

#include "bvh/bvh.h"
#include "scene/scene.h"
#include "vk/buffer.h"

namespace vkdr {

class VulkanContext;

// The scene as the stages read it: triangles and their attributes in BVH leaf order,
// the BVH, materials, media, textures and the emitter CDF.
struct GpuScene {
    Buffer triangleVertices;
    Buffer triangleUvs;
    Buffer triangleInfo;
    Buffer bvhNodes;
    Buffer materials;
    Buffer media;
    Buffer textures;
    Buffer texels;
    Buffer lightTriangles;
    Buffer lightCdf;
    uint32_t lightCount = 0;
    float rayEpsilon = 0.0f;  // scene units
};

GpuScene uploadScene(const VulkanContext& context, const Scene& scene, const Bvh& bvh);

// Uploads what the differentiable parameters change (materials, media, texels, the
// emitter distribution) again, for new parameter values of the same geometry.
void uploadSceneParameters(const VulkanContext& context, const Scene& scene, std::span<const uint32_t> triangleOrder,
                           GpuScene& gpu);

}  // namespace vkdr
