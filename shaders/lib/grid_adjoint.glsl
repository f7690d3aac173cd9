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
