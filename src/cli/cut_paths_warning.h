#pragma once
#include <cstdint>
#include <string>

namespace vkdr {

// Tells the user, on stderr, that `paths` paths reached the renderer's bound on segments
// per path and were cut short; nothing when there were none. `renders` says whose paths
// they are: "the render", "the renders of the iterations run".
void warnOfCutPaths(uint64_t paths, const std::string& renders);

}  // namespace vkdr
