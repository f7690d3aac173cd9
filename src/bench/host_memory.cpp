#include "bench/host_memory.h"

#include <malloc.h>
#include <sys/resource.h>

#include <fstream>

#include "core/proc_memory.h"

namespace vkdr {

void resetPeakHostResidentBytes() {
    malloc_trim(0);
    // "5" resets the peak resident set size to the current one (Linux 4.0 and later).
    std::ofstream("/proc/self/clear_refs") << "5";
}

uint64_t peakHostResidentBytes() {
    if (uint64_t peak = procKilobytes("/proc/self/status", "VmHWM"); peak > 0) {
        return peak;
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return uint64_t(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

}  // namespace vkdr
