#include "cli/cut_paths_warning.h"

#include <cstdio>

namespace vkdr {

void warnOfCutPaths(uint64_t paths) {
    if (paths == 0) {
        return;
    }
    // A segment ends at every medium boundary a path crosses and at every pause of free
    // flight through a dense grid, besides its scattering depth.
    std::fprintf(stderr,
                 "warning: %llu paths crossed too many medium boundaries or paused too often in a dense grid and "
                 "were cut short; the image lacks the light beyond\n",
                 static_cast<unsigned long long>(paths));
}

}  // namespace vkdr
