#pragma once
#include <chrono>

namespace vkdr {

// When the process started, for the times it reports as the whole run's: set during
// static initialisation, before main runs (and before any device is set up).
inline const std::chrono::steady_clock::time_point kProcessStart = std::chrono::steady_clock::now();

}  // namespace vkdr
