#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "diff/rendered_loss_gradient.h"
#include "scene/parameter_kinds.h"

namespace vkdr {

// One component's finite difference: its step and the range its evaluations stay in.
struct FiniteDifferenceStep {
    double step = 0.0;
    ValueRange range;
};

// The step and range of every component of every parameter, by parameter and component:
// each kind's step, or where neither a central nor a one-sided difference fits the range
// (a scene-wide medium's emission near its bound), half the wider side's room. Throws,
// naming the component and its range, where float has no room at all; call it before
// any rendering.
std::vector<std::vector<FiniteDifferenceStep>> finiteDifferenceSteps(const Scene& scene,
                                                                      const std::vector<std::string>& parameters);

// One component of one parameter: the adjoint gradient against central finite
// differences of the loss with common random numbers, each the mean over several seeds
// with its standard error.
struct GradientCheckRow {
    std::string name;
    int component = 0;
    double adjoint = 0.0, adjointError = 0.0;
    double finiteDifference = 0.0, finiteDifferenceError = 0.0;
    double step = 0.0;
    // False where, at every seed, the losses the difference takes (at x + h and x - h, or
    // at x, x + h and x + 2h) were equal bit for bit: the gradient is zero, or too small
    // for a step to change any pixel's float, and the difference cannot tell which.
    bool finiteDifferenceResolved = true;
};

// The steps checkGradients tells `progress` of: an adjoint evaluation per seed, and a
// finite difference per value and seed.
size_t gradientCheckSteps(const Scene& scene, const std::vector<std::string>& parameters, int seeds);

// Each component's step is its kind's (scene/parameter_kinds.h). Where value - h would
// leave the kind's range (sigma = 0, base colour 0) or value + h would (g at 0.99), the
// second-order one-sided difference (-3 L(x) + 4 L(x + h) - L(x + 2h)) / 2h, or its
// mirror, is used instead; so too where a scene-wide medium's sigma or emission would
// leave the range that keeps its emission bounded (scene/scene_medium_emission.h).
// Where neither fits, the step shrinks to fit (finiteDifferenceSteps). The adjoint is
// taken at seeds firstSeed, firstSeed + 1, ..., the finite differences at seeds 2^20
// further on (modulo 2^32), so that the two share no samples. Parameter names must be
// valid for the scene. `atFirstSeed`, where given, is the adjoint evaluation at
// firstSeed already made (grad's own), taken instead of evaluating it again, and counted
// as its step done. `progress` is told the fraction done within and after each
// evaluation of the adjoint (through lossGradient.reportProgress, which it leaves unset)
// and after each seed's finite difference.
std::vector<GradientCheckRow> checkGradients(RenderedLossGradient& lossGradient, const Scene& scene,
                                             const std::vector<std::string>& parameters, int seeds,
                                             uint32_t firstSeed = 0,
                                             const std::function<void(double)>& progress = {},
                                             const GradientResult* atFirstSeed = nullptr);

}  // namespace vkdr
