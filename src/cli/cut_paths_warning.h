#pragma once
#include <cstdint>

namespace vkdr {

// Tells the user, on stderr, that `paths` paths of a render reached the renderer's bound
// on segments per path and were cut short; nothing when there were none.
void warnOfCutPaths(uint64_t paths);

}  // namespace vkdr
