#pragma once
#include <map>
#include <string>
#include <vector>

#include "diff/loss_gradient.h"

namespace vkdr {

// A LossGradient plus a smoothness term for density grids: for each named density
// parameter (media/<medium>/density) with weight w,
//   w * (1 / voxels) * sum over pairs of face-neighbouring voxels (d_i - d_j)^2,
// added to the loss, and its exact gradient to the parameter's. It ties each voxel to its
// neighbours, which a reconstruction needs where views see a voxel weakly or its
// gradient is noisy: without it such voxels wander while the image loss still falls.
class SmoothedLossGradient : public LossGradient {
public:
    // `inner` must outlive this; every named parameter must be a density grid's.
    SmoothedLossGradient(LossGradient& inner, std::map<std::string, double> weights);
    GradientResult evaluate(const Scene& scene, uint32_t seed) override;

private:
    LossGradient& inner_;
    std::map<std::string, double> weights_;
};

// The weight of the smoothness term for each density grid among `parameters`: `weight`
// for each, none when it is 0. Throws vkdr::Error when the weight is not 0 but no
// density grid is among them.
std::map<std::string, double> smoothnessWeights(const std::vector<std::string>& parameters, double weight);

// The smoothness term of one grid, and (when `gradient` is not null, sized as the
// grid's values) its gradient added to *gradient.
double gridSmoothness(const DensityGrid& grid, double weight, std::vector<double>* gradient);

}  // namespace vkdr
