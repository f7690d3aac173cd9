#include "cli/warnings.h"

#include <cstdio>

#include "render/cut_paths.h"

namespace vkdr {

void printWarning(const std::string& text) {
    std::fprintf(stderr, "warning: %s\n", text.c_str());
}

void warnOfCutPaths(uint64_t paths, const std::string& renders) {
    if (paths > 0) {
        printWarning(cutPathsMessage(paths, renders));
    }
}

}  // namespace vkdr
