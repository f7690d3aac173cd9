// Reading density grids: a voxel, the trilinear density between voxel centres, and the
// majorant cells (device_types.h, GpuDensityGrid). grid_tracking.glsl walks them.
#ifndef VKDR_DENSITY_GRID_GLSL
#define VKDR_DENSITY_GRID_GLSL

float gridVoxel(GpuDensityGrid grid, ivec3 voxel) {
    ivec3 local = voxel - grid.firstVoxel.xyz;
    if (any(lessThan(local, ivec3(0))) || any(greaterThanEqual(local, grid.size.xyz))) {
        return 0.0f;
    }
    return P.gridValues.v[grid.firstVoxel.w + (local.z * grid.size.y + local.y) * grid.size.x + local.x];
}

float gridMajorant(GpuDensityGrid grid, ivec3 cell) {
    return P.gridMajorants.v[grid.size.w + (cell.z * grid.majorantCells.y + cell.y) * grid.majorantCells.x + cell.x];
}

#endif
