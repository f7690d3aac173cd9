#pragma once
#include <cmath>
#include <optional>

#include "scene/scene.h"

namespace vkdr {

// Whether `halfExtent` (a half width or height of an orthographic view: glTF's xmag or
// ymag) is one the renderer takes: > 0 and finite as the float it is held in, so that a
// value that rounds to 0 does not leave a camera that is not orthographic.
inline bool usableOrthographicHalfExtent(double halfExtent) {
    return halfExtent > 0.0 && float(halfExtent) > 0.0f && std::isfinite(float(halfExtent));
}

// An orthographic camera's rays start across a rectangle of its XY plane: `halfWidth` by
// `halfHeight` about its position. They all start in one medium, the medium at the
// camera's position, only where no medium boundary crosses or touches that rectangle.
// The index of the first material whose boundary triangles do (within 1e-5 of the
// coordinates' magnitude), or nothing.
std::optional<uint32_t> boundaryAcrossOrthographicView(const Scene& scene, const Camera& camera, double halfWidth,
                                                       double halfHeight);

}  // namespace vkdr
