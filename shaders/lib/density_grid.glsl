// Reading density grids: a voxel, the trilinear density between voxel centres, and the
// majorant cells (device_types.h, GpuDensityGrid). grid_tracking.glsl walks them.
#ifndef VKDR_DENSITY_GRID_GLSL
#define VKDR_DENSITY_GRID_GLSL

// Where the voxel at index coordinates `voxel` sits in RenderParams.gridValues (its first
// channel; its gradients among the density gradients alike); -1 outside the grid's box,
// where every value is 0 and no parameter exists.
int gridVoxelOffset(GpuDensityGrid grid, ivec3 voxel) {
    ivec3 local = voxel - ivec3(grid.firstVoxel);
    if (any(lessThan(local, ivec3(0))) || any(greaterThanEqual(local, ivec3(grid.size)))) {
        return -1;
    }
    return grid.firstVoxel.w + grid.majorantCells.w * ((local.z * grid.size.y + local.y) * grid.size.x + local.x);
}

float gridVoxel(GpuDensityGrid grid, ivec3 voxel) {
    int offset = gridVoxelOffset(grid, voxel);
    return offset < 0 ? 0.0f : P.gridValues.v[offset];
}

// An RGB voxel (an albedo grid's); 0 outside the box.
vec3 gridVoxelRgb(GpuDensityGrid grid, ivec3 voxel) {
    int offset = gridVoxelOffset(grid, voxel);
    return offset < 0 ? vec3(0.0f)
                      : vec3(P.gridValues.v[offset], P.gridValues.v[offset + 1], P.gridValues.v[offset + 2]);
}

float gridMajorant(GpuDensityGrid grid, ivec3 cell) {
    return P.gridMajorants.v[grid.size.w + (cell.z * grid.majorantCells.y + cell.y) * grid.majorantCells.x + cell.x];
}

#endif
