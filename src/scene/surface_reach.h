#pragma once
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace vkdr {

// Within this fraction of the coordinates' magnitude a point is on a surface as far as
// the renderer's rays can tell: its offsets off surfaces are of this size.
inline constexpr double kOnSurfaceRelative = 1e-5;

// The largest absolute coordinate of `p`.
inline double coordinateMagnitude(const glm::dvec3& p) {
    return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

}  // namespace vkdr
