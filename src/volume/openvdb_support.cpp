#include "volume/openvdb_support.h"

#include <cmath>
#include <sstream>

#include "core/format_text.h"

namespace vkdr {

void initializeOpenVdb() {
    static const bool initialized = (openvdb::initialize(), true);
    (void)initialized;
}

glm::dmat4 toGlm(const openvdb::math::Mat4d& matrix) {
    glm::dmat4 result;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) result[i][j] = matrix[i][j];
    }
    return result;
}

openvdb::math::Mat4d toOpenVdb(const glm::dmat4& matrix) {
    openvdb::math::Mat4d result;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) result[i][j] = matrix[i][j];
    }
    return result;
}

openvdb::math::Transform::Ptr exactTransform(const glm::dmat4& indexToLocal) {
    // Reading a transform keeps the map it reads as it is: serialise the AffineMap and
    // read it back.
    std::stringstream bytes;
    openvdb::io::setCurrentVersion(bytes);
    openvdb::writeString(bytes, openvdb::math::AffineMap::mapType());
    openvdb::math::AffineMap(toOpenVdb(indexToLocal)).write(bytes);
    auto transform = std::make_shared<openvdb::math::Transform>();
    transform->read(bytes);
    return transform;
}

std::string openVdbMapProblem(const glm::dmat4& indexToLocal) {
    try {
        openvdb::math::AffineMap map(toOpenVdb(indexToLocal));
    } catch (const openvdb::ArithmeticError&) {
        return formatText("its voxels are too small for OpenVDB (a voxel's volume is %g; OpenVDB's transforms "
                          "need at least 3e-15, voxels about 1.44e-5 across)",
                          std::abs(glm::determinant(glm::dmat3(indexToLocal))));
    }
    return "";
}

}  // namespace vkdr
