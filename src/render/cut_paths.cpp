#include "render/cut_paths.h"

namespace vkdr {

std::string cutPathsMessage(uint64_t paths, const std::string& renders) {
    // A segment ends at every medium boundary a path crosses and at every pause of free
    // flight through a dense grid, besides its scattering depth.
    return std::to_string(paths) + " paths of " + renders +
           " crossed too many medium boundaries or paused too often in a dense grid and were cut short, losing "
           "the light beyond";
}

}  // namespace vkdr
