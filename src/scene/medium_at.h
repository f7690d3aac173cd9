#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkdr {

// The medium containing `point` (e.g. a camera position): kNoMedium for vacuum.
// Casts one ray against the medium boundaries: leaving through a boundary means the
// point is inside it; entering one means the point is in that boundary's outside
// medium; no boundary at all means the scene medium. Brute force over the boundary
// triangles, so call it per camera, not per pixel.
int32_t mediumAt(const Scene& scene, glm::vec3 point);

}  // namespace vkdr
