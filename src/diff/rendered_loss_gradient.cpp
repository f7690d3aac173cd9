#include "diff/rendered_loss_gradient.h"

#include <algorithm>
#include <utility>

#include "bvh/bvh.h"
#include "core/error.h"
#include "device_types.h"
#include "diff/gradient_slots.h"
#include "render/renderer.h"
#include "scene/parameters.h"

namespace vkdr {

// Views of one image size share a renderer (Renderer::setCamera): one copy of the scene
// on the device, and one gradient sum read back per evaluation however many views
// there are.
struct ViewsOfOneSize {
    std::unique_ptr<Renderer> renderer;
    std::vector<size_t> views;  // indices into Impl::targets
};

struct RenderedLossGradient::Impl {
    std::vector<TargetView> targets;
    std::vector<ViewsOfOneSize> groups;
    std::vector<GradientSlot> slots;
    ProgressCallback progress;  // of each evaluation

    // Checks the views and the parameter names before anything is built.
    Impl(const Scene& scene, std::vector<TargetView> views, const std::vector<std::string>& parameters)
        : targets(std::move(views)) {
        if (targets.empty()) {
            throw Error("no target image given");
        }
        slots = resolveGradientSlots(scene, parameters);
    }

    void addRenderers(const VulkanContext& context, const Scene& scene, const Bvh& bvh, const RenderSettings& settings,
                      LossKind loss) {
        const DerivativeTargets derivativeTargets = derivativeTargetsOf(slots);
        for (size_t v = 0; v < targets.size(); ++v) {
            const Image& target = targets[v].target;
            auto sameSize = std::find_if(groups.begin(), groups.end(), [&](const ViewsOfOneSize& group) {
                return group.renderer->width() == target.width && group.renderer->height() == target.height;
            });
            if (sameSize != groups.end()) {
                sameSize->renderer->setCamera(scene, targets[v].camera);  // refuses an unknown camera now
                sameSize->views.push_back(v);
                continue;
            }
            RenderSettings viewSettings = settings;
            viewSettings.camera = targets[v].camera;
            viewSettings.width = target.width;
            viewSettings.height = target.height;
            auto renderer = std::make_unique<Renderer>(context, scene, bvh, viewSettings);
            renderer->enableGradients(target, loss, derivativeTargets);
            groups.push_back({std::move(renderer), {v}});
        }
    }

    // Points the group's renderer at view v with the random numbers of `seed`.
    void prepareView(ViewsOfOneSize& group, const Scene& scene, size_t v, uint32_t seed) const;
};

uint32_t viewSeed(uint32_t seed, size_t view) {
    return seed * 2654435761u + uint32_t(view) * 40503u;
}

void RenderedLossGradient::Impl::prepareView(ViewsOfOneSize& group, const Scene& scene, size_t v,
                                              uint32_t seed) const {
    if (group.views.size() > 1) {  // a renderer of one view keeps its camera and target
        group.renderer->setCamera(scene, targets[v].camera);
        group.renderer->setTarget(targets[v].target);
    }
    group.renderer->setSeed(viewSeed(seed, v));
}

RenderedLossGradient::RenderedLossGradient(const VulkanContext& context, const Scene& scene,
                                           std::vector<TargetView> views, std::vector<std::string> parameters,
                                           const RenderSettings& settings, LossKind loss)
    : impl_(std::make_unique<Impl>(scene, std::move(views), parameters)) {
    impl_->addRenderers(context, scene, buildBvh(scene.positions, scene.triangles), settings, loss);
}

RenderedLossGradient::RenderedLossGradient(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                                           std::vector<TargetView> views, std::vector<std::string> parameters,
                                           const RenderSettings& settings, LossKind loss)
    : impl_(std::make_unique<Impl>(scene, std::move(views), parameters)) {
    impl_->addRenderers(context, scene, bvh, settings, loss);
}

RenderedLossGradient::~RenderedLossGradient() = default;

double RenderedLossGradient::loss(const Scene& scene, uint32_t seed) {
    double total = 0.0;
    for (ViewsOfOneSize& group : impl_->groups) {
        group.renderer->setParameters(scene);
        for (size_t v : group.views) {
            impl_->prepareView(group, scene, v, seed);
            total += group.renderer->loss();
        }
    }
    return total / double(impl_->targets.size());
}

void RenderedLossGradient::requireRenderable(const Scene& scene, uint32_t seed) {
    loss(scene, seed);
}

void RenderedLossGradient::reportProgress(ProgressCallback progress) {
    impl_->progress = std::move(progress);
}

GradientResult RenderedLossGradient::evaluate(const Scene& scene, uint32_t seed) {
    const ProgressCallback& progress = impl_->progress;
    GradientResult result;
    result.images.resize(impl_->targets.size());
    std::vector<std::vector<double>> gradients(impl_->slots.size());
    // The loss is the views' mean, and so is its gradient.
    const double viewWeight = 1.0 / double(impl_->targets.size());
    // A view's image, loss, times and cut paths go into the result; its gradients are returned.
    auto addView = [&](size_t v, const Renderer& renderer, GradientEvaluation evaluation) {
        result.images[v] = std::move(evaluation.image);
        result.loss += viewWeight * evaluation.loss;
        result.forwardMs += evaluation.forwardMs;
        result.adjointMs += evaluation.adjointMs;
        result.truncatedPaths += renderer.stats().truncatedPaths;
        return std::move(evaluation.gradients);
    };
    // Each view is an equal share of the whole.
    size_t viewsDone = 0;
    auto viewProgress = [&]() -> ProgressCallback {
        if (!progress) return {};
        return [&progress, &viewsDone, views = double(impl_->targets.size())](double fraction) {
            progress((double(viewsDone) + fraction) / views);
        };
    };
    for (ViewsOfOneSize& group : impl_->groups) {
        Renderer& renderer = *group.renderer;
        renderer.setParameters(scene);
        SceneGradients sum;
        if (group.views.size() == 1) {
            // One view renders, back-propagates and reads everything back in one go.
            impl_->prepareView(group, scene, group.views[0], seed);
            sum = addView(group.views[0], renderer, renderer.renderWithGradients(viewProgress()));
            ++viewsDone;
        } else {
            renderer.clearGradientSum();
            for (size_t v : group.views) {
                impl_->prepareView(group, scene, v, seed);
                addView(v, renderer, renderer.renderAddingGradients(viewProgress()));
                ++viewsDone;
            }
            sum = renderer.downloadGradientSum();
        }
        for (size_t i = 0; i < impl_->slots.size(); ++i) {
            const GradientSlot& slot = impl_->slots[i];
            gradients[i].resize(slot.valueCount(), 0.0);
            addWeightedGradient(slot, sum, viewWeight, gradients[i]);
        }
    }
    for (size_t i = 0; i < impl_->slots.size(); ++i) {
        result.parameters.push_back({impl_->slots[i].name, getParameter(scene, impl_->slots[i].name),
                                     std::move(gradients[i])});
    }
    return result;
}

}  // namespace vkdr
