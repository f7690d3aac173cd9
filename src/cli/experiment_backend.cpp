#include "cli/experiment_backend.h"

#include <map>
#include <set>
#include <string>

#include "bvh/bvh.h"
#include "diff/rendered_loss_gradient.h"
#include "render/renderer.h"

namespace vkdr {
namespace {

// What a renderer is built for: every field of RenderSettings that render() depends on
// but the seed, which changes freely as the parameter values do (keptRadianceBytes
// matters to gradients only).
std::string rendererKey(const RenderSettings& settings) {
    return settings.camera + ' ' + std::to_string(settings.width) + 'x' + std::to_string(settings.height) + ' ' +
           std::to_string(settings.spp) + ' ' + std::to_string(settings.maxDepth) + ' ' +
           std::to_string(settings.pathsPerPass) + (settings.equiangularSampling ? "" : " no-equiangular");
}

struct RenderersOfRepeatedViews {
    std::set<std::string> rendered;
    std::map<std::string, std::unique_ptr<Renderer>> kept;
};

}  // namespace

ExperimentBackend renderingBackend(const VulkanContext& context, const Bvh& bvh, ProgressCallback evaluationProgress) {
    auto renderers = std::make_shared<RenderersOfRepeatedViews>();
    ExperimentBackend backend;
    backend.render = [&context, &bvh, renderers](const Scene& scene, const RenderSettings& settings) {
        const std::string key = rendererKey(settings);
        if (auto found = renderers->kept.find(key); found != renderers->kept.end()) {
            found->second->setParameters(scene);
            found->second->setSeed(settings.seed);
            return found->second->render();
        }
        if (renderers->rendered.insert(key).second) {
            return Renderer(context, scene, bvh, settings).render();
        }
        auto renderer = std::make_unique<Renderer>(context, scene, bvh, settings);
        return renderers->kept.emplace(key, std::move(renderer)).first->second->render();
    };
    backend.makeLossGradient = [&context, &bvh, evaluationProgress](
                                   const Scene& scene, std::vector<TargetView> views,
                                   std::vector<std::string> parameters, const RenderSettings& settings,
                                   LossKind loss) -> std::unique_ptr<LossGradient> {
        auto lossGradient = std::make_unique<RenderedLossGradient>(context, scene, bvh, std::move(views),
                                                                   std::move(parameters), settings, loss);
        lossGradient->reportProgress(evaluationProgress);
        return lossGradient;
    };
    return backend;
}

}  // namespace vkdr
