#include "volume/index_transform.h"

#include <cmath>

#include "core/format_text.h"

namespace vkdr {

std::string indexTransformProblem(const glm::dmat4& indexToLocal) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            if (!std::isfinite(indexToLocal[column][row])) return "the transform has a non-finite entry";
        }
    }
    const glm::dvec4 lastRow(indexToLocal[0][3], indexToLocal[1][3], indexToLocal[2][3], indexToLocal[3][3]);
    if (lastRow != glm::dvec4(0.0, 0.0, 0.0, 1.0)) {
        return formatText("the transform is not affine (its last row is %g %g %g %g, not 0 0 0 1)", lastRow.x,
                          lastRow.y, lastRow.z, lastRow.w);
    }
    const glm::dmat3 axes(indexToLocal);
    const double edges = glm::length(axes[0]) * glm::length(axes[1]) * glm::length(axes[2]);
    const double volume = std::abs(glm::determinant(axes));
    if (!(volume >= 1e-6 * edges) || volume == 0.0) {
        return formatText("the transform is singular (its voxel axes (%g %g %g), (%g %g %g), (%g %g %g) are "
                          "linearly dependent or nearly so)",
                          axes[0].x, axes[0].y, axes[0].z, axes[1].x, axes[1].y, axes[1].z, axes[2].x, axes[2].y,
                          axes[2].z);
    }
    return "";
}

}  // namespace vkdr
