#pragma once
#include <cstdint>
#include <string>

namespace vkdr {

// What to tell the user when `paths` paths of `renders` ("the render", "the renders of
// the iterations run") reached the renderer's bound on segments per path and were cut
// short (RenderStats::truncatedPaths): a sentence without the "warning: " the command
// line puts before it.
std::string cutPathsMessage(uint64_t paths, const std::string& renders);

}  // namespace vkdr
