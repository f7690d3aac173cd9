#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "bench/gradient_noise.h"
#include "image/image.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace vkdr {

class VulkanContext;
struct Bvh;

// The parameter whose gradient bench measures: sigma_s of the scene's first medium, or
// its sigma_a where sigma_s is 0 in every channel or has no gradient (a density grid's
// with a channel at 0); nothing for a scene without media, or whose first medium has
// neither.
std::optional<std::string> benchGradientParameter(const Scene& scene);

// The gradient is taken with every channel of the parameter at this many times the
// value the target was rendered with, where the L2 loss's gradient is far from 0 (at the
// target's value it is 0 in expectation). Lower rather than higher: a dense medium's image
// changes little as it grows denser, so there the gradient is small beside its noise
// and its mean, the denominator of the relative noise, is poorly resolved
// (docs/performance.md).
inline constexpr float kGradientParameterScale = 0.5f;

// The spread and cost of one parameter's gradient.
struct GradientBenchmark {
    std::string parameter;  // as grad and optimize name it: media/fog/sigma_s
    uint32_t seeds = 0;
    double evaluationMs = 0.0;           // median wall clock of one evaluation
    std::optional<GradientNoise> noise;  // over the seeds (gradientNoise): nullopt with fewer than 2
    // 1 / (relative noise^2 x evaluation seconds); none without a relative noise, or
    // with one of 0.
    std::optional<double> efficiency() const;
};

// Evaluates, with RenderedLossGradient as grad and optimize do, the L2 loss's gradient
// with respect to benchGradientParameter(scene) at `seeds` seeds (0, 1, ...), with the
// parameter at kGradientParameterScale times its value and `target` rendered at the
// scene's own values: the sum of its channels' gradients, the derivative with respect to
// one value that sets every channel. `bvh` is the scene's; `settings` give the spp, depth,
// camera and paths per pass, the target the size; `afterEach` runs after every
// timed evaluation, which follow one warm-up evaluation at seed `seeds`. nullopt for a
// scene without the parameter, or for 0 seeds.
std::optional<GradientBenchmark> benchmarkGradient(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                                                   const Image& target, const RenderSettings& settings, uint32_t seeds,
                                                   const std::function<void()>& afterEach);

}  // namespace vkdr
