#pragma once
#include <map>
#include <string>
#include <vector>

#include "diff/loss_gradient.h"
#include "optimize/optimize_loop.h"

namespace vkdr {

// What a fit of density grids knows besides the images, as terms added to the loss with
// their exact gradients (docs/density-grids.md, "Fitting a grid"). Per-voxel gradients
// are noisy and a voxel is seen through few paths; without priors the voxels the views
// see weakly wander while the image loss still falls.
// The largest weight a prior takes, from the command line or an experiment file.
inline constexpr double kMostGridPriorWeight = 1e12;

struct GridPriorWeights {
    // w * (1 / voxels) * sum over pairs of face-neighbouring voxels (d_i - d_j)^2: ties
    // each voxel to its neighbours.
    double smoothness = 0.0;
    // w * (1 / voxels) * sum of d_i, the mean density (its L1 norm, densities being >= 0):
    // empties what the images do not ask to fill, as smoke leaves most of its box empty.
    double sparsity = 0.0;
    // w * (1 / voxels) * sum over pairs of face-neighbouring voxels |d_i - d_j| (the grid's
    // anisotropic total variation): like smoothness it ties neighbours together, but a
    // step costs its height, not its square, so edges stay sharp.
    double totalVariation = 0.0;

    bool any() const { return smoothness != 0.0 || sparsity != 0.0 || totalVariation != 0.0; }
};

// A LossGradient plus the priors of each named density parameter (media/<medium>/density).
class GridPriorLossGradient : public LossGradient {
public:
    // `inner` must outlive this; every named parameter must be a density grid's.
    GridPriorLossGradient(LossGradient& inner, std::map<std::string, GridPriorWeights> weights);
    GradientResult evaluate(const Scene& scene, uint32_t seed) override;
    void requireRenderable(const Scene& scene, uint32_t seed) override { inner_.requireRenderable(scene, seed); }

private:
    LossGradient& inner_;
    std::map<std::string, GridPriorWeights> weights_;
};

// The weights `options` gives.
inline GridPriorWeights gridPriorWeightsOf(const OptimizeOptions& options) {
    return {options.smoothness, options.sparsity, options.totalVariation};
}

// `weights` for each density grid among `parameters`; none when every weight is 0.
// Throws vkdr::Error when a weight is not 0 but no density grid is among them.
std::map<std::string, GridPriorWeights> gridPriorWeights(const std::vector<std::string>& parameters,
                                                         GridPriorWeights weights);

// The experiment key of the first weight that is not 0 (the weight gridPriorWeights'
// error is about).
const char* firstWeightName(const GridPriorWeights& weights);

// Each term of one grid, and (when `gradient` is not null, sized as the grid's values) its
// gradient added to *gradient.
double gridSmoothness(const DensityGrid& grid, double weight, std::vector<double>* gradient);
double gridSparsity(const DensityGrid& grid, double weight, std::vector<double>* gradient);
// Where two neighbours are equal, the gradient of |d_i - d_j| is taken as 0 (a subgradient).
double gridTotalVariation(const DensityGrid& grid, double weight, std::vector<double>* gradient);

}  // namespace vkdr
