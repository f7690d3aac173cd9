#pragma once
#include <cstdint>
#include <filesystem>
#include <list>
#include <memory>
#include <mutex>
#include <sys/types.h>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "diff/gradient_slots.h"
#include "diff/loss_gradient.h"
#include "image/image.h"
#include "render/render_settings.h"
#include "render/renderer.h"
#include "scene/load_scene.h"
#include "scene/parameter_kinds.h"
#include "vk/context.h"

namespace vkdr {

// A named parameter as the Python module presents it: its array shape ((3,) for RGB,
// (1,) for g, (height, width, 3) for a texture) and the range its values must lie in.
struct ParameterInfo {
    std::string name;
    std::vector<size_t> shape;
    ValueRange range;
    // The other names of the same values: the base colour textures of the materials that
    // share this one's texture.
    std::vector<std::string> aliases;
};

// One loaded scene on one device, for the Python module: renders, differentiates an
// image adjoint the caller computed, reads and sets parameters, and writes the scene
// back. It drives the same Renderer as the command line; renderers (one per camera,
// size, samples and depth) are kept between calls, so a loop that renders the same view
// again pays no pipeline or buffer set-up. Calls from several threads take turns: the
// device's queue and the cached renderers serve one call at a time.
class SceneSession {
public:
    SceneSession(const std::filesystem::path& file, const std::string& device, bool allowOutsideFiles);
    ~SceneSession();

    const std::filesystem::path& file() const { return file_; }
    const std::vector<std::string>& warnings() const { return warnings_; }
    const VulkanContext& context() const { return *context_; }
    const Scene& scene() const { return loaded_.scene; }

    std::vector<ParameterInfo> parameters() const;
    ParameterInfo parameter(const std::string& name) const;
    std::vector<float> get(const std::string& name) const;
    // One value sets every channel (and texel); otherwise as many values as the parameter has.
    void set(const std::string& name, const std::vector<float>& values);

    // Each call says how many of its paths were cut short by the renderer's bound on
    // segments per path (RenderStats::truncatedPaths; 0 in a faithful render).
    struct Rendered {
        Image image;
        uint64_t cutPaths = 0;
    };
    Rendered render(const RenderSettings& settings);
    // dLoss/dparameter for each name, for the image adjoint dLoss/dI of render(settings)'s
    // image (Renderer::backpropagate).
    struct Backpropagated {
        std::vector<ParameterGradient> gradients;
        uint64_t cutPaths = 0;
    };
    Backpropagated backpropagate(const RenderSettings& settings, const Image& imageAdjoint,
                                 const std::vector<std::string>& names);

    // The command line's loss and gradient (grad, optimize): the image of render(settings),
    // its loss against `target`, and dLoss/dparameter for each name by the split-sample
    // estimator (Renderer::renderWithGradients).
    struct LossGradient {
        double loss;
        Image image;
        std::vector<ParameterGradient> gradients;
        uint64_t cutPaths = 0;
    };
    LossGradient lossGradient(const RenderSettings& settings, const Image& target, LossKind loss,
                              const std::vector<std::string>& names);

    // The scene with the current parameter values as a .gltf (scene/write_scene.h); never
    // over the scene file or a file it reads.
    void write(const std::filesystem::path& out) const;

private:
    struct CachedRenderer;
    // The renderer for these settings, made (or moved to the front of renderers_) and
    // given the current parameters and the settings' seed. `input` (an image adjoint or a
    // target, named `what` in errors), where given, must have the render's size; an
    // unknown camera or an input of another size is refused before any cached renderer
    // is evicted.
    CachedRenderer& rendererFor(const RenderSettings& settings, const Image* input = nullptr,
                                const std::string& what = "");
    // work(cached) with the renderer rendererFor() returned last; any exception discards
    // it. What is checked before the call (an input's size) keeps it.
    template <typename Work>
    auto withRenderer(CachedRenderer& cached, Work work);

    std::vector<ParameterGradient> namedGradients(const std::vector<GradientSlot>& slots,
                                                  const SceneGradients& gradients) const;
    // Every public call's lock, in the process that made the session only: a child forked
    // from it (a DataLoader's worker) has its memory but not the device's threads, and
    // would wait for them for ever (or for a lock another thread held at the fork).
    std::unique_lock<std::recursive_mutex> lockInOwnProcess() const;

    mutable std::recursive_mutex mutex_;  // held by every public call; they call each other
    std::filesystem::path file_;
    LoadedScene loaded_;
    std::vector<std::string> warnings_;
    Bvh bvh_;
    std::unique_ptr<VulkanContext> context_;
    std::list<CachedRenderer> renderers_;  // most recently used first
    uint64_t parameterVersion_ = 0;        // counts set() calls, so renderers know when to upload
    pid_t process_;                        // the process that made it
};

}  // namespace vkdr
