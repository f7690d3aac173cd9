#pragma once
#include <memory>
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "render/path_progress.h"
#include "render/render_settings.h"

namespace vkdr {

class VulkanContext;
struct Bvh;

// LossGradient by path replay on the GPU: each view is rendered, and its paths are
// replayed in adjoint mode, accumulating parameter gradients with atomic adds
// (docs/design.md, "The adjoint"; Renderer::renderWithGradients).
// The scene's geometry and cameras are fixed at construction; evaluate() takes new
// parameter values.
class RenderedLossGradient : public LossGradient {
public:
    // settings: spp, max depth and paths per pass; each view's size is its target's.
    RenderedLossGradient(const VulkanContext& context, const Scene& scene, std::vector<TargetView> views,
                         std::vector<std::string> parameters, const RenderSettings& settings, LossKind loss);
    // The same with the scene's BVH at hand (buildBvh of its positions and triangles),
    // for a caller that has built it already.
    RenderedLossGradient(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                         std::vector<TargetView> views, std::vector<std::string> parameters,
                         const RenderSettings& settings, LossKind loss);
    ~RenderedLossGradient() override;

    GradientResult evaluate(const Scene& scene, uint32_t seed) override;
    // Each later evaluate() tells `progress` the share of it done as the views' paths
    // end; an empty callback, the default, reports nothing.
    void reportProgress(ProgressCallback progress);
    // Renders every view once, as loss() does.
    void requireRenderable(const Scene& scene, uint32_t seed) override;
    // The loss alone, rendered with the random numbers evaluate() uses for its image:
    // finite differences over it share their noise (common random numbers).
    double loss(const Scene& scene, uint32_t seed);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The seed that view number `view` (in the order given) renders with in an evaluation at
// `seed`: each view has random numbers of its own.
uint32_t viewSeed(uint32_t seed, size_t view);

}  // namespace vkdr
