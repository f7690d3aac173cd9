#pragma once
// The adjoint's gradient of every parameter component as a mean and standard error
// over independent evaluations: the left-hand side of every statistical gradient test.
#include <cstdint>
#include <vector>

#include "core/sample_statistics.h"
#include "diff/loss_gradient.h"

namespace vkdr::test {

// [parameter][component], over evaluations with seeds 0 .. seeds - 1.
inline std::vector<std::vector<MeanAndError>> gradientOverSeeds(LossGradient& lossGradient, const Scene& scene,
                                                               uint32_t seeds) {
    std::vector<std::vector<std::vector<double>>> samples;
    for (uint32_t seed = 0; seed < seeds; ++seed) {
        GradientResult result = lossGradient.evaluate(scene, seed);
        samples.resize(result.parameters.size());
        for (size_t p = 0; p < result.parameters.size(); ++p) {
            samples[p].resize(result.parameters[p].gradient.size());
            for (size_t c = 0; c < result.parameters[p].gradient.size(); ++c) {
                samples[p][c].push_back(result.parameters[p].gradient[c]);
            }
        }
    }
    std::vector<std::vector<MeanAndError>> gradients(samples.size());
    for (size_t p = 0; p < samples.size(); ++p) {
        for (const std::vector<double>& component : samples[p]) {
            gradients[p].push_back(meanAndError(component));
        }
    }
    return gradients;
}

}  // namespace vkdr::test
