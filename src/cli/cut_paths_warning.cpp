#include "cli/cut_paths_warning.h"

#include <cstdio>

namespace vkdr {

void warnOfCutPaths(uint64_t paths, const std::string& renders) {
    if (paths == 0) {
        return;
    }
    // A segment ends at every medium boundary a path crosses and at every pause of free
    // flight through a dense grid, besides its scattering depth.
    std::fprintf(stderr,
                 "warning: %llu paths of %s crossed too many medium boundaries or paused too often in a dense grid "
                 "and were cut short, losing the light beyond\n",
                 static_cast<unsigned long long>(paths), renders.c_str());
}

}  // namespace vkdr
