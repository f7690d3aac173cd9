#include "optimize/coarse_grid_gradient.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vkdr {
namespace {

size_t voxelCount(glm::ivec3 size) { return size_t(size.x) * size_t(size.y) * size_t(size.z); }

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

std::vector<AxisFootprint> axisFootprints(int axis, glm::ivec3 size, uint32_t divisor) {
    const glm::ivec3 coarse = coarseGridSize(size, divisor);
    std::vector<AxisFootprint> footprints;
    for (int i = 0; i < size[axis]; ++i) footprints.push_back(axisFootprint(i, divisor, coarse[axis]));
    return footprints;
}

glm::ivec3 withAxis(glm::ivec3 size, int axis, int count) {
    size[axis] = count;
    return size;
}

// Trilinear interpolation is separable, U = U_z U_y U_x, so U and U^T apply one axis at a
// time: along `axis`, every line of voxels of `in` (inSize) becomes the line of `out`
// (the same size but along `axis`). U takes a line of coarse values to fine ones,
// U^T (`transposed`) adds each fine value into its two coarse ones. Lines are
// independent, so they run in parallel, and each is summed in one order: the same bits
// on any number of threads.
void applyAlongAxis(int axis, const std::vector<AxisFootprint>& footprints, bool transposed, glm::ivec3 inSize,
                    std::span<const double> in, glm::ivec3 outSize, std::span<double> out) {
    const auto strides = [](glm::ivec3 s) { return glm::u64vec3(1, uint64_t(s.x), uint64_t(s.x) * uint64_t(s.y)); };
    const glm::u64vec3 inStride = strides(inSize), outStride = strides(outSize);
    const int across = (axis + 1) % 3, other = (axis + 2) % 3;
    const size_t lines = size_t(inSize[across]) * size_t(inSize[other]);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lines), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t line = range.begin(); line != range.end(); ++line) {
            const size_t a = line % size_t(inSize[across]), b = line / size_t(inSize[across]);
            const size_t inBase = a * inStride[across] + b * inStride[other];
            const size_t outBase = a * outStride[across] + b * outStride[other];
            const size_t inStep = inStride[axis], outStep = outStride[axis];
            if (transposed) {
                for (int c = 0; c < outSize[axis]; ++c) out[outBase + size_t(c) * outStep] = 0.0;
                for (size_t i = 0; i < footprints.size(); ++i) {
                    const AxisFootprint& f = footprints[i];
                    const double value = in[inBase + i * inStep];
                    out[outBase + size_t(f.low) * outStep] += (1.0 - f.weight) * value;
                    out[outBase + size_t(f.high) * outStep] += f.weight * value;
                }
            } else {
                for (size_t i = 0; i < footprints.size(); ++i) {
                    const AxisFootprint& f = footprints[i];
                    out[outBase + i * outStep] = (1.0 - f.weight) * in[inBase + size_t(f.low) * inStep] +
                                                 f.weight * in[inBase + size_t(f.high) * inStep];
                }
            }
        }
    });
}

// U (coarse to fine) or U^T (`transposed`: fine to coarse) along x, then y, then z.
void applyAxisByAxis(glm::ivec3 size, uint32_t divisor, bool transposed, std::span<const double> in,
                     std::span<double> out) {
    const glm::ivec3 coarse = coarseGridSize(size, divisor);
    const glm::ivec3 target = transposed ? coarse : size;
    glm::ivec3 from = transposed ? size : coarse;
    // x reads `in` and z writes `out`; y goes between two arrays of its own.
    std::vector<double> afterX, afterY;
    std::span<const double> values = in;
    for (int axis = 0; axis < 3; ++axis) {
        const glm::ivec3 to = withAxis(from, axis, target[axis]);
        std::span<double> next = out;
        if (axis < 2) {
            std::vector<double>& kept = axis == 0 ? afterX : afterY;
            kept.resize(voxelCount(to));
            next = kept;
        }
        applyAlongAxis(axis, axisFootprints(axis, size, divisor), transposed, from, values, to, next);
        values = next;
        from = to;
    }
}

}  // namespace

glm::ivec3 coarseGridSize(glm::ivec3 size, uint32_t divisor) {
    const int d = int(divisor);
    return (size + glm::ivec3(d - 1)) / d;
}

void prolongGrid(glm::ivec3 size, uint32_t divisor, std::span<const double> coarse, std::span<double> fine) {
    applyAxisByAxis(size, divisor, false, coarse, fine);
}

void prolongGridTransposed(glm::ivec3 size, uint32_t divisor, std::span<const double> fine,
                           std::span<double> coarse) {
    applyAxisByAxis(size, divisor, true, fine, coarse);
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
