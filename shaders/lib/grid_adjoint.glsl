// The adjoint of tracking through a density grid (docs/density-grids.md, "Gradients").
// A path segment's factor in channel c is T_c = exp(-sigma_t,c D), D the density's
// integral along it, times sigma_s,c d(x) where it scatters. The derivatives of log T are
// integrals along the segment, which stratified points of their own estimate without
// bias, independently of the tracking that chose the path.
#ifndef VKDR_GRID_ADJOINT_GLSL
#define VKDR_GRID_ADJOINT_GLSL
#include "adjoint.glsl"
#include "grid_tracking.glsl"

// Whether the adjoint pipelines add any gradient that tracking through a grid touches.
bool gridGradientsWanted() {
    return gradientWanted(kGradientKindSigmaA) || gradientWanted(kGradientKindSigmaS) ||
           gradientWanted(kGradientKindDensity);
}

// Adds g times each of the point's trilinear weights (gridDensity's footprint) to the
// gradient of its voxel, in any grid (a density, emission or albedo grid): channel c of
// each voxel gets g[c] times the weight, for the grid's `channels` (1 or 3, a constant at
// every call, so that the loop unrolls). Voxels outside the grid's box are not
// parameters. The lanes of a subgroup seldom add to the same voxel, so each adds alone
// (addFixedPointFromOneLane) into its subgroup's copy of the sums.
void addTrilinearGradient(GpuDensityGrid grid, vec3 index, vec3 g, uint channels) {
    vec3 base = floor(index);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = trilinearCorner(corner);
        int voxel = gridVoxelOffset(grid, ivec3(base) + offset);
        if (voxel >= 0) {
            vec3 weighted = g * trilinearWeight(index - base, offset);
            for (uint c = 0u; c < channels; ++c) {
                addFixedPointFromOneLane(P.densityGradients,
                                         subgroupCopyOfSum(P.densityGradientsCopyStride, uint(voxel) + c), weighted[c]);
            }
        }
    }
}

void addTrilinearDensityGradient(GpuDensityGrid grid, vec3 index, float g) {
    if (gradientWanted(kGradientKindDensity)) {
        addTrilinearGradient(grid, index, vec3(g), 1u);
    }
}

// An unbiased estimate of D over [0, tMax) of the ray from its kDensityIntegralPoints
// points (offset by u in their strata). With `voxelWeight` != 0 it also adds
// -voxelWeight dD/d(voxel) to every voxel's gradient: d log T_c / d(voxel) is
// -sigma_t,c dD/d(voxel), so voxelWeight is the sum over channels of sigma_t,c times the
// adjoint weight of T_c.
float densityIntegralAdjoint(GpuDensityGrid grid, vec3 origin, vec3 direction, float tMax, float u,
                             float voxelWeight) {
    GridRay ray = gridRay(grid, origin, direction);
    vec2 interval = cellsInterval(grid, ray, tMax);
    if (!(interval.x < interval.y)) {
        return 0.0f;  // the ray misses the grid (or its interval is not finite)
    }
    float length = (interval.y - interval.x) / float(kDensityIntegralPoints);
    float integral = 0.0f;
    for (uint k = 0u; k < kDensityIntegralPoints; ++k) {
        vec3 point = densityIntegralPoint(ray, interval, k, u);
        integral += length * gridDensity(grid, point);
        if (voxelWeight != 0.0f) {
            addTrilinearDensityGradient(grid, point, -voxelWeight * length);
        }
    }
    return integral;
}

#endif
