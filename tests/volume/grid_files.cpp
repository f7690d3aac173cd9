#include "grid_files.h"

#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "volume/openvdb_support.h"

namespace vkdr::test {

glm::dmat4 skewedTransform() {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(1.5, -2.0, 0.25));
    m = glm::rotate(m, 0.7, glm::normalize(glm::dvec3(1.0, 2.0, 3.0)));
    return glm::scale(m, glm::dvec3(0.1, 0.25, 0.05));
}

DensityGrid patternedGrid(glm::ivec3 first, glm::ivec3 size, const glm::dmat4& indexToLocal) {
    DensityGrid grid;
    grid.name = "density";
    grid.firstVoxel = first;
    grid.size = size;
    grid.indexToLocal = indexToLocal;
    grid.values.resize(grid.voxelCount());
    for (size_t i = 0; i < grid.values.size(); ++i) grid.values[i] = float(i % 7) / 3.0f + 1.0f / 7.0f;
    // A zero inside the box, where it leaves the active box unchanged.
    if (glm::all(glm::greaterThanEqual(size, glm::ivec3(3)))) {
        const glm::ivec3 centre = size / 2;
        grid.values[(size_t(centre.z) * size_t(size.y) + size_t(centre.y)) * size_t(size.x) + size_t(centre.x)] = 0.0f;
    }
    return grid;
}

void writeOpenVdbGrid(const std::filesystem::path& file, const openvdb::GridBase::Ptr& grid) {
    initializeOpenVdb();
    openvdb::io::File(file.string()).write(openvdb::GridPtrVec{grid});
}

openvdb::FloatGrid::Ptr openVdbGrid(const DensityGrid& grid) {
    initializeOpenVdb();
    openvdb::FloatGrid::Ptr vdb = openvdb::FloatGrid::create(0.0f);
    vdb->setName(grid.name);
    vdb->setTransform(exactTransform(grid.indexToLocal));
    auto accessor = vdb->getAccessor();
    for (int z = 0; z < grid.size.z; ++z) {
        for (int y = 0; y < grid.size.y; ++y) {
            for (int x = 0; x < grid.size.x; ++x) {
                const glm::ivec3 voxel = grid.firstVoxel + glm::ivec3(x, y, z);
                if (grid.at(voxel) != 0.0f) accessor.setValue(openvdb::Coord(voxel.x, voxel.y, voxel.z), grid.at(voxel));
            }
        }
    }
    return vdb;
}

std::string fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

}  // namespace vkdr::test
