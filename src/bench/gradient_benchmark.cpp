#include "bench/gradient_benchmark.h"

#include <vector>

#include <glm/glm.hpp>

#include "bench/efficiency.h"
#include "bench/median.h"
#include "core/milliseconds_of.h"
#include "diff/gradient_over_seeds.h"
#include "diff/gradient_slots.h"
#include "diff/rendered_loss_gradient.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"

namespace vkdr {
namespace {

// Another LossGradient, with the wall clock of each evaluation.
class TimedLossGradient : public LossGradient {
public:
    TimedLossGradient(LossGradient& timed, const std::function<void()>& afterEach)
        : timed_(timed), afterEach_(afterEach) {}

    GradientResult evaluate(const Scene& scene, uint32_t seed) override {
        GradientResult result;
        milliseconds_.push_back(millisecondsOf([&] { result = timed_.evaluate(scene, seed); }));
        if (afterEach_) {
            afterEach_();
        }
        return result;
    }

    const std::vector<double>& milliseconds() const { return milliseconds_; }

private:
    LossGradient& timed_;
    const std::function<void()>& afterEach_;
    std::vector<double> milliseconds_;
};

}  // namespace

std::optional<std::string> benchGradientParameter(const Scene& scene) {
    if (scene.media.empty()) {
        return std::nullopt;
    }
    const Medium& medium = scene.media.front();
    if (glm::any(glm::greaterThan(medium.sigma_s, glm::vec3(0.0f))) && hasSigmaSGradient(medium)) {
        return parameterName(ParameterKind::SigmaS, medium.name);
    }
    if (glm::any(glm::greaterThan(medium.sigma_a, glm::vec3(0.0f)))) {
        return parameterName(ParameterKind::SigmaA, medium.name);
    }
    return std::nullopt;
}

std::optional<double> GradientBenchmark::efficiency() const {
    return noise && noise->relativeNoise ? efficiencyOf(*noise->relativeNoise, evaluationMs * 1e-3) : std::nullopt;
}

std::optional<GradientBenchmark> benchmarkGradient(const VulkanContext& context, const Scene& scene, const Bvh& bvh,
                                                   const Image& target, const RenderSettings& settings, uint32_t seeds,
                                                   const std::function<void()>& afterEach) {
    const std::optional<std::string> parameter = benchGradientParameter(scene);
    if (!parameter || seeds == 0) {
        return std::nullopt;
    }
    Scene perturbed = scene;
    std::vector<float> value = getParameter(scene, *parameter);
    for (float& channel : value) {
        channel *= kGradientParameterScale;
    }
    setParameter(perturbed, *parameter, value);

    RenderedLossGradient lossGradient(context, perturbed, bvh, {{settings.camera, target}}, {*parameter}, settings,
                                      LossKind::L2);
    lossGradient.evaluate(perturbed, seeds);  // warm-up, at a seed the figures do not use
    TimedLossGradient timed(lossGradient, afterEach);
    const std::vector<std::vector<double>> channels = gradientSamplesOverSeeds(timed, perturbed, seeds).front();
    std::vector<double> estimates(seeds, 0.0);
    for (const std::vector<double>& channel : channels) {
        for (uint32_t s = 0; s < seeds; ++s) {
            estimates[s] += channel[s];
        }
    }
    return GradientBenchmark{*parameter, seeds, median(timed.milliseconds()), gradientNoise(estimates)};
}

}  // namespace vkdr
