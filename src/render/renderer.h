#pragma once
#include <cstdint>
#include <functional>
#include <memory>

#include "bvh/bvh.h"
#include "image/image.h"
#include "render/gpu_scene.h"
#include "render/path_buffers.h"
#include "render/render_settings.h"
#include "render/stage_pipelines.h"
#include "scene/scene.h"

namespace vkdr {

class VulkanContext;

struct RenderStats {
    uint64_t paths = 0;
    uint64_t rays = 0;            // closest-hit and shadow rays traced
    uint64_t truncatedPaths = 0;  // paths cut by the segment limit (should be 0)
    double seconds = 0.0;         // wall time of render(), uploads excluded
};

// Progress in [0, 1], called after every pass.
using ProgressCallback = std::function<void(double)>;

// The wavefront path tracer: uploads a scene once, then renders it pass by pass.
class Renderer {
public:
    Renderer(const VulkanContext& context, const Scene& scene, const Bvh& bvh, const RenderSettings& settings);

    Image render(const ProgressCallback& progress = {});
    const RenderStats& stats() const { return stats_; }
    int width() const { return int(camera_.width); }
    int height() const { return int(camera_.height); }

private:
    struct PassRange {
        uint32_t firstPixel, pixelCount, firstSample, samplesInPass;
    };
    void runPass(const PassRange& range);
    void recordSegment(class CommandRecorder& recorder, const gpu::PassConstants& constants, uint32_t currentRays);
    gpu::RenderParams renderParams() const;

    const VulkanContext& context_;
    RenderSettings settings_;
    gpu::GpuCamera camera_;
    glm::vec3 background_;
    GpuScene scene_;
    StagePipelines pipelines_;
    std::unique_ptr<PathBuffers> paths_;
    Buffer params_;
    RenderStats stats_;
};

}  // namespace vkdr
