#pragma once
// Memory figures Linux gives in /proc.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace vkdr {

// The value in kB of the line "<key>: <value> kB" of a /proc file, in bytes; 0 if absent.
inline uint64_t procKilobytes(const char* file, const std::string& key) {
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

// Memory the system could still give the process without swapping (MemAvailable).
inline uint64_t availableHostBytes() {
    if (uint64_t available = procKilobytes("/proc/meminfo", "MemAvailable"); available > 0) {
        return available;
    }
    return uint64_t(sysconf(_SC_AVPHYS_PAGES)) * uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace vkdr
