#pragma once
#include <cmath>
#include <limits>
#include <optional>

#include "scene/scene.h"

namespace vkdr {

// Whether `halfExtent` (a half width or height of an orthographic view: glTF's xmag or
// ymag) is one the renderer takes: a normal float, finite, not 0 and not subnormal (a
// device may flush a subnormal to 0, which would leave a camera that is not orthographic).
inline bool usableOrthographicHalfExtent(double halfExtent) {
    return float(halfExtent) >= std::numeric_limits<float>::min() && std::isfinite(float(halfExtent));
}

// An orthographic camera's rays start across a rectangle of its XY plane: `halfWidth` by
// `halfHeight` about its position. They all start in one medium, the medium at the
// camera's position, only where no medium boundary crosses or touches that rectangle.
// The index of the first material whose boundary triangles do (within 1e-5 of the
// coordinates' magnitude), or nothing.
std::optional<uint32_t> boundaryAcrossOrthographicView(const Scene& scene, const Camera& camera, double halfWidth,
                                                       double halfHeight);

}  // namespace vkdr
