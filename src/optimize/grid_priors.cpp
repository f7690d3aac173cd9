#include "optimize/grid_priors.h"

#include <cmath>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/error.h"
#include "optimize/density_grid_options.h"
#include "scene/parameter_kinds.h"
#include "scene/parameters.h"

namespace vkdr {

namespace {

// weight / voxels * sum over face-neighbour pairs of penalty(d_i - d_j), adding to each
// voxel's gradient weight / voxels * the sum over its face neighbours j of
// penalty'(d_i - d_j) (penalty' is odd: the pair's derivative by d_j is penalty'(d_j - d_i)).
// Layers of voxels run in parallel, each gathering into its own voxels' gradients, and
// the layers' penalties add up in a fixed tree: the same bits on any number of threads.
template <typename Penalty, typename Derivative>
double neighbourPenalty(const DensityGrid& grid, double weight, std::vector<double>* gradient, Penalty penalty,
                        Derivative derivative) {
    const size_t voxels = grid.voxelCount();
    if (voxels == 0 || weight == 0.0) {
        return 0.0;
    }
    const double scale = weight / double(voxels);
    const size_t strides[3] = {1, size_t(grid.size.x), size_t(grid.size.x) * size_t(grid.size.y)};
    const auto layers = [&](const tbb::blocked_range<int>& range, double sum) {
        for (int z = range.begin(); z != range.end(); ++z) {
            for (int y = 0; y < grid.size.y; ++y) {
                for (int x = 0; x < grid.size.x; ++x) {
                    const glm::ivec3 voxel(x, y, z);
                    const size_t i = x * strides[0] + y * strides[1] + z * strides[2];
                    const double value = grid.values[i];
                    double slope = 0.0;
                    for (int axis = 0; axis < 3; ++axis) {
                        if (voxel[axis] + 1 < grid.size[axis]) {
                            const double difference = value - grid.values[i + strides[axis]];
                            sum += penalty(difference);
                            slope += derivative(difference);
                        }
                        if (voxel[axis] > 0) slope += derivative(value - grid.values[i - strides[axis]]);
                    }
                    if (gradient) (*gradient)[i] += scale * slope;
                }
            }
        }
        return sum;
    };
    return scale * tbb::parallel_deterministic_reduce(tbb::blocked_range<int>(0, grid.size.z, 1), 0.0, layers,
                                                      std::plus<double>());
}

}  // namespace

const char* firstWeightName(const GridPriorWeights& weights) {
    if (weights.smoothness != 0.0) return "smoothness";
    return weights.sparsity != 0.0 ? "sparsity" : "total_variation";
}

double gridSmoothness(const DensityGrid& grid, double weight, std::vector<double>* gradient) {
    return neighbourPenalty(
        grid, weight, gradient, [](double d) { return d * d; }, [](double d) { return 2.0 * d; });
}

double gridTotalVariation(const DensityGrid& grid, double weight, std::vector<double>* gradient) {
    return neighbourPenalty(
        grid, weight, gradient, [](double d) { return std::abs(d); },
        [](double d) { return d > 0.0 ? 1.0 : d < 0.0 ? -1.0 : 0.0; });
}

double gridSparsity(const DensityGrid& grid, double weight, std::vector<double>* gradient) {
    const size_t voxels = grid.voxelCount();
    if (voxels == 0 || weight == 0.0) {
        return 0.0;
    }
    const double scale = weight / double(voxels);
    double sum = 0.0;
    for (size_t i = 0; i < voxels; ++i) {
        sum += grid.values[i];
        if (gradient) (*gradient)[i] += scale;
    }
    return scale * sum;
}

GridPriorLossGradient::GridPriorLossGradient(LossGradient& inner, std::map<std::string, GridPriorWeights> weights)
    : inner_(inner), weights_(std::move(weights)) {}

GradientResult GridPriorLossGradient::evaluate(const Scene& scene, uint32_t seed) {
    GradientResult result = inner_.evaluate(scene, seed);
    for (const auto& [name, weight] : weights_) {
        const DensityGrid* grid = densityGridOf(scene, name);
        if (!grid) throw Error("grid priors: " + name + " is not a grid (a density or an emission grid)");
        std::vector<double>* gradient = nullptr;
        for (ParameterGradient& parameter : result.parameters) {
            if (parameter.name == name) {
                gradient = &parameter.gradient;
            }
        }
        result.loss += gridSmoothness(*grid, weight.smoothness, gradient);
        result.loss += gridSparsity(*grid, weight.sparsity, gradient);
        result.loss += gridTotalVariation(*grid, weight.totalVariation, gradient);
    }
    return result;
}

std::map<std::string, GridPriorWeights> gridPriorWeights(const std::vector<std::string>& parameters,
                                                         GridPriorWeights weights) {
    std::map<std::string, GridPriorWeights> named;
    if (!weights.any()) return named;
    requireADensityGridAmong(parameters, std::string("a ") + firstWeightName(weights) + " weight is");
    for (const std::string& name : parameters) {
        const std::optional<ParsedParameterName> parsed = parseParameterName(name);
        if (parsed && isScalarGridKind(parsed->description->kind)) named[name] = weights;
    }
    return named;
}

}  // namespace vkdr
