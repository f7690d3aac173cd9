#include "diff/rendered_loss_gradient.h"

#include "bvh/bvh.h"
#include "core/error.h"
#include "device_types.h"
#include "diff/gradient_slots.h"
#include "render/renderer.h"
#include "scene/parameters.h"

namespace vkdr {

struct RenderedLossGradient::Impl {
    std::vector<std::unique_ptr<Renderer>> views;  // one per target view
    std::vector<GradientSlot> slots;

    // Checks the views and the parameter names before anything is built.
    Impl(const Scene& scene, const std::vector<TargetView>& targets, const std::vector<std::string>& parameters) {
        if (targets.empty()) {
            throw Error("no target image given");
        }
        slots = resolveGradientSlots(scene, parameters);
    }

    void addViews(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                  const std::vector<TargetView>& targets, const RenderSettings& settings, LossKind loss) {
        const DerivativeTargets derivativeTargets = derivativeTargetsOf(slots);
        for (const TargetView& view : targets) {
            RenderSettings viewSettings = settings;
            viewSettings.camera = view.camera;
            viewSettings.width = view.target.width;
            viewSettings.height = view.target.height;
            auto renderer = std::make_unique<Renderer>(context, scene, bvh, viewSettings);
            renderer->enableGradients(view.target, loss, derivativeTargets);
            views.push_back(std::move(renderer));
        }
    }
};

namespace {

// Each view gets its own random numbers.
uint32_t viewSeed(uint32_t seed, size_t view) {
    return seed * 2654435761u + uint32_t(view) * 40503u;
}

}  // namespace

RenderedLossGradient::RenderedLossGradient(const VulkanContext& context, const Scene& scene,
                                           std::vector<TargetView> views, std::vector<std::string> parameters,
                                           const RenderSettings& settings, LossKind loss)
    : impl_(std::make_unique<Impl>(scene, views, parameters)) {
    impl_->addViews(context, scene, buildBvh(scene.positions, scene.triangles), views, settings, loss);
}

RenderedLossGradient::RenderedLossGradient(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                                           std::vector<TargetView> views, std::vector<std::string> parameters,
                                           const RenderSettings& settings, LossKind loss)
    : impl_(std::make_unique<Impl>(scene, views, parameters)) {
    impl_->addViews(context, scene, bvh, views, settings, loss);
}

RenderedLossGradient::~RenderedLossGradient() = default;

double RenderedLossGradient::loss(const Scene& scene, uint32_t seed) {
    double total = 0.0;
    for (size_t v = 0; v < impl_->views.size(); ++v) {
        Renderer& renderer = *impl_->views[v];
        renderer.setParameters(scene);
        renderer.setSeed(viewSeed(seed, v));
        total += renderer.loss();
    }
    return total / double(impl_->views.size());
}

GradientResult RenderedLossGradient::evaluate(const Scene& scene, uint32_t seed) {
    GradientResult result;
    std::vector<std::vector<double>> gradients(impl_->slots.size());
    const double viewWeight = 1.0 / double(impl_->views.size());
    for (size_t v = 0; v < impl_->views.size(); ++v) {
        Renderer& renderer = *impl_->views[v];
        renderer.setParameters(scene);
        renderer.setSeed(viewSeed(seed, v));
        GradientEvaluation evaluation = renderer.renderWithGradients();
        result.images.push_back(std::move(evaluation.image));
        result.loss += viewWeight * evaluation.loss;
        result.forwardMs += evaluation.forwardMs;
        result.adjointMs += evaluation.adjointMs;
        const SceneGradients& g = evaluation.gradients;
        for (size_t i = 0; i < impl_->slots.size(); ++i) {
            std::vector<double> values = gatherGradient(impl_->slots[i], g);
            gradients[i].resize(values.size(), 0.0);
            for (size_t k = 0; k < values.size(); ++k) {
                gradients[i][k] += viewWeight * values[k];
            }
        }
    }
    for (size_t i = 0; i < impl_->slots.size(); ++i) {
        result.parameters.push_back({impl_->slots[i].name, getParameter(scene, impl_->slots[i].name), gradients[i]});
    }
    return result;
}

}  // namespace vkdr
