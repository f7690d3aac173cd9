#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vkdr {

// A voxel grid of scalars (a density, an emission strength) or of RGB values (an albedo)
// held densely over the bounding box of its active voxels. Voxel centres sit at integer
// index coordinates (OpenVDB's convention); values between them are trilinear, and every
// voxel outside the box (or inactive in the file) is 0.
struct DensityGrid {
    std::string name;               // the grid's name in its file
    glm::ivec3 firstVoxel{0};       // index coordinates of values[0]
    glm::ivec3 size{0};             // voxels along x, y, z; 0 in any axis: an empty grid
    glm::dmat4 indexToLocal{1.0};   // the file's own index-to-world transform (affine)
    int channels = 1;               // values per voxel: 1, or 3 for RGB
    // size.x * size.y * size.z voxels, x fastest, then y, then z; `channels` values each
    std::vector<float> values;

    size_t voxelCount() const { return size_t(size.x) * size_t(size.y) * size_t(size.z); }
    // Channel `channel` of the voxel at index coordinates `voxel`; 0 outside the box.
    float at(glm::ivec3 voxel, int channel = 0) const {
        glm::ivec3 local = voxel - firstVoxel;
        if (glm::any(glm::lessThan(local, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(local, size))) {
            return 0.0f;
        }
        const size_t index = (size_t(local.z) * size_t(size.y) + size_t(local.y)) * size_t(size.x) + size_t(local.x);
        return values[index * size_t(channels) + size_t(channel)];
    }
};

}  // namespace vkdr
