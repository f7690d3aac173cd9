#include "volume/index_transform.h"

#include <algorithm>
#include <cmath>

#include "core/format_text.h"

namespace vkdr {
namespace {

// `axis` scaled to length 1 without squaring its entries (which could overflow or
// underflow); (0, 0, 0) for the zero axis.
glm::dvec3 unitAxis(const glm::dvec3& axis) {
    const double largest = std::max({std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)});
    if (largest == 0.0) return glm::dvec3(0.0);
    const glm::dvec3 scaled = axis / largest;
    return scaled / glm::length(scaled);
}

}  // namespace

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
    // The volume of the unit voxel axes: how far from flat the voxels are, whatever
    // their size (a product of the lengths themselves can overflow or underflow).
    const glm::dmat3 unitAxes(unitAxis(axes[0]), unitAxis(axes[1]), unitAxis(axes[2]));
    const double volume = std::abs(glm::determinant(unitAxes));
    if (!(volume >= 1e-6)) {
        return formatText("the transform is singular (its voxel axes (%g %g %g), (%g %g %g), (%g %g %g) are "
                          "linearly dependent or nearly so)",
                          axes[0].x, axes[0].y, axes[0].z, axes[1].x, axes[1].y, axes[1].z, axes[2].x, axes[2].y,
                          axes[2].z);
    }
    return "";
}

}  // namespace vkdr
