#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/loss_kind.h"
#include "scene/scene.h"

namespace vkdr {

// One view of the scene to match: a camera (by name; empty = the first) and its target.
struct TargetView {
    std::string camera;
    Image target;
};

// dLoss/dparameter for one named parameter (names as in scene/parameters.h).
struct ParameterGradient {
    std::string name;
    std::vector<float> value;       // the value the gradient was taken at
    std::vector<double> gradient;   // same length as value
};

struct GradientResult {
    double loss = 0.0;                          // mean of the views' losses
    std::vector<ParameterGradient> parameters;  // in the order they were requested
    std::vector<Image> images;                  // the rendered image of each view
    double forwardMs = 0.0;                     // primal rendering, all views
    double adjointMs = 0.0;                     // replay and adjoint, all views
    uint64_t truncatedPaths = 0;                // paths cut by the segment limit, all views (should be 0)
};

// The loss of a scene's renders against target views, and its gradient with respect to
// chosen parameters. The optimiser sees only this interface, so it can be tested
// against analytic functions.
class LossGradient {
public:
    virtual ~LossGradient() = default;
    // Renders every view with `scene`'s current parameter values; `seed` picks the
    // random numbers (an optimiser passes a new one each iteration).
    virtual GradientResult evaluate(const Scene& scene, uint32_t seed) = 0;
    // Throws UnrenderableValuesError where `scene`'s current values do not render (a grid
    // medium too dense to track): an optimiser asks it of the values its last step left,
    // which no evaluation renders. What cannot fail to render checks nothing.
    virtual void requireRenderable(const Scene&, uint32_t /*seed*/) {}
};

}  // namespace vkdr
