#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/sample_statistics.h"
#include "diff/loss_gradient.h"

namespace vkdr {

// Every parameter component's gradient from evaluations with seeds firstSeed ..
// firstSeed + seeds - 1: [parameter][component][seed]. `evaluated` is called after each.
// `atFirstSeed`, where given, is the evaluation at firstSeed already made, taken in its
// place.
std::vector<std::vector<std::vector<double>>> gradientSamplesOverSeeds(LossGradient& lossGradient,
                                                                       const Scene& scene, uint32_t seeds,
                                                                       uint32_t firstSeed = 0,
                                                                       const std::function<void()>& evaluated = {},
                                                                       const GradientResult* atFirstSeed = nullptr);

// The gradient of every parameter component as a mean and standard error over
// evaluations with seeds firstSeed .. firstSeed + seeds - 1: [parameter][component].
std::vector<std::vector<MeanAndError>> gradientOverSeeds(LossGradient& lossGradient, const Scene& scene,
                                                         uint32_t seeds, uint32_t firstSeed = 0,
                                                         const std::function<void()>& evaluated = {},
                                                         const GradientResult* atFirstSeed = nullptr);

}  // namespace vkdr
