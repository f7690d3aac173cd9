#pragma once
#include <optional>

#include "scene/scene.h"

namespace vkdr {

// An orthographic camera's rays start across a rectangle of its XY plane: `halfWidth` by
// `halfHeight` about its position. They all start in one medium, the medium at the
// camera's position, only where no medium boundary crosses or touches that rectangle.
// The index of the first material whose boundary triangles do (within 1e-5 of the
// coordinates' magnitude), or nothing.
std::optional<uint32_t> boundaryAcrossOrthographicView(const Scene& scene, const Camera& camera, double halfWidth,
                                                       double halfHeight);

}  // namespace vkdr
