#include "optimize/coarse_grid_gradient.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vkdr {
namespace {

// The two coarse voxels a fine voxel interpolates along one axis, and the second's weight.
struct AxisFootprint {
    int low = 0;
    int high = 0;
    double weight = 0.0;
};

AxisFootprint axisFootprint(int fine, uint32_t divisor, int coarseCount) {
    const double at = std::clamp((double(fine) + 0.5) / double(divisor) - 0.5, 0.0, double(coarseCount - 1));
    AxisFootprint footprint;
    footprint.low = std::min(int(std::floor(at)), coarseCount - 1);
    footprint.high = std::min(footprint.low + 1, coarseCount - 1);
    footprint.weight = at - double(footprint.low);
    return footprint;
}

// Calls visit(fineIndex, coarseIndex, weight) for each of the (up to) eight coarse voxels
// of each fine voxel.
template <typename Visit>
void forEachWeight(glm::ivec3 size, uint32_t divisor, Visit visit) {
    const glm::ivec3 coarse = coarseGridSize(size, divisor);
    std::vector<AxisFootprint> axes[3];
    for (int axis = 0; axis < 3; ++axis) {
        for (int i = 0; i < size[axis]; ++i) axes[axis].push_back(axisFootprint(i, divisor, coarse[axis]));
    }
    size_t fine = 0;
    for (int z = 0; z < size.z; ++z) {
        for (int y = 0; y < size.y; ++y) {
            for (int x = 0; x < size.x; ++x, ++fine) {
                const AxisFootprint& fx = axes[0][size_t(x)];
                const AxisFootprint& fy = axes[1][size_t(y)];
                const AxisFootprint& fz = axes[2][size_t(z)];
                for (int corner = 0; corner < 8; ++corner) {
                    const bool hx = corner & 1, hy = corner & 2, hz = corner & 4;
                    const double weight = (hx ? fx.weight : 1.0 - fx.weight) * (hy ? fy.weight : 1.0 - fy.weight) *
                                          (hz ? fz.weight : 1.0 - fz.weight);
                    if (weight == 0.0) continue;
                    const size_t index = (size_t(hz ? fz.high : fz.low) * size_t(coarse.y) +
                                          size_t(hy ? fy.high : fy.low)) * size_t(coarse.x) +
                                         size_t(hx ? fx.high : fx.low);
                    visit(fine, index, weight);
                }
            }
        }
    }
}

size_t voxelCount(glm::ivec3 size) { return size_t(size.x) * size_t(size.y) * size_t(size.z); }

}  // namespace

glm::ivec3 coarseGridSize(glm::ivec3 size, uint32_t divisor) {
    const int d = int(divisor);
    return (size + glm::ivec3(d - 1)) / d;
}

void prolongGrid(glm::ivec3 size, uint32_t divisor, std::span<const double> coarse, std::span<double> fine) {
    std::fill(fine.begin(), fine.end(), 0.0);
    forEachWeight(size, divisor, [&](size_t f, size_t c, double weight) { fine[f] += weight * coarse[c]; });
}

void prolongGridTransposed(glm::ivec3 size, uint32_t divisor, std::span<const double> fine,
                           std::span<double> coarse) {
    std::fill(coarse.begin(), coarse.end(), 0.0);
    forEachWeight(size, divisor, [&](size_t f, size_t c, double weight) { coarse[c] += weight * fine[f]; });
}

void coarsenGridGradient(glm::ivec3 size, uint32_t divisor, std::span<double> gradient) {
    if (divisor <= 1) return;
    std::vector<double> coarse(voxelCount(coarseGridSize(size, divisor)));
    prolongGridTransposed(size, divisor, gradient, coarse);
    prolongGrid(size, divisor, coarse, gradient);
}

uint32_t gridDivisorAt(uint32_t iteration, uint32_t iterations, uint32_t levels) {
    if (levels <= 1 || iterations == 0) return 1;
    const uint32_t level = uint32_t(uint64_t(std::min(iteration, iterations - 1)) * levels / iterations);
    return 1u << (levels - 1 - level);
}

}  // namespace vkdr
