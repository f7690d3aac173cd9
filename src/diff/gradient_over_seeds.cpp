#include "diff/gradient_over_seeds.h"

namespace vkdr {

std::vector<std::vector<std::vector<double>>> gradientSamplesOverSeeds(LossGradient& lossGradient,
                                                                       const Scene& scene, uint32_t seeds,
                                                                       uint32_t firstSeed,
                                                                       const std::function<void()>& evaluated,
                                                                       const GradientResult* atFirstSeed) {
    std::vector<std::vector<std::vector<double>>> samples;
    // Counted, not compared with firstSeed + seeds: seeds wrap modulo 2^32.
    for (uint32_t i = 0; i < seeds; ++i) {
        const bool known = i == 0 && atFirstSeed;
        GradientResult evaluatedHere;
        if (!known) evaluatedHere = lossGradient.evaluate(scene, firstSeed + i);
        const GradientResult& result = known ? *atFirstSeed : evaluatedHere;
        samples.resize(result.parameters.size());
        for (size_t p = 0; p < result.parameters.size(); ++p) {
            samples[p].resize(result.parameters[p].gradient.size());
            for (size_t c = 0; c < result.parameters[p].gradient.size(); ++c) {
                samples[p][c].push_back(result.parameters[p].gradient[c]);
            }
        }
        if (evaluated && !known) evaluated();
    }
    return samples;
}

std::vector<std::vector<MeanAndError>> gradientOverSeeds(LossGradient& lossGradient, const Scene& scene,
                                                         uint32_t seeds, uint32_t firstSeed,
                                                         const std::function<void()>& evaluated,
                                                         const GradientResult* atFirstSeed) {
    const std::vector<std::vector<std::vector<double>>> samples =
        gradientSamplesOverSeeds(lossGradient, scene, seeds, firstSeed, evaluated, atFirstSeed);
    std::vector<std::vector<MeanAndError>> gradients(samples.size());
    for (size_t p = 0; p < samples.size(); ++p) {
        for (const std::vector<double>& component : samples[p]) {
            gradients[p].push_back(meanAndError(component));
        }
    }
    return gradients;
}

}  // namespace vkdr
