#include "bench/host_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace vkdr {
namespace {

// The value in kB of the line "<key>: <value> kB" of a /proc file, in bytes; 0 if absent.
uint64_t procKilobytes(const char* file, const std::string& key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.starts_with(key + ":")) {
            std::istringstream value(line.substr(key.size() + 1));
            uint64_t kilobytes = 0;
            value >> kilobytes;
            return kilobytes * 1024;
        }
    }
    return 0;
}

}  // namespace

void resetPeakHostResidentBytes() {
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

uint64_t availableHostBytes() {
    if (uint64_t available = procKilobytes("/proc/meminfo", "MemAvailable"); available > 0) {
        return available;
    }
    return uint64_t(sysconf(_SC_AVPHYS_PAGES)) * uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace vkdr
