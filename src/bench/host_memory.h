#pragma once
#include <cstdint>

namespace vkdr {

// Starts a new measurement of the peak resident set (Linux: /proc/self/clear_refs);
// where the kernel does not allow it, the peak stays the process's lifetime peak. Memory
// freed before is first returned to the system (malloc_trim), so that what malloc kept
// of it does not count as resident in the new measurement.
void resetPeakHostResidentBytes();

// The most host memory the process has held resident since the last reset: VmHWM of
// /proc/self/status, or getrusage's ru_maxrss where that cannot be read.
uint64_t peakHostResidentBytes();

}  // namespace vkdr
