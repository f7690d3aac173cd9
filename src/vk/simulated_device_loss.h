#pragma once

namespace vkdr {

// VKDR_SIMULATE_DEVICE_LOST=N: the Nth queue submission of the process (counted from 1)
// and every later one are not made, and report VK_ERROR_DEVICE_LOST instead. A GPU that
// resets mid-run is hard to come by, and lavapipe never does; this lets the tests check
// what a run says and leaves behind when it happens. Unset, nothing is simulated.
bool deviceLossSimulated();

}  // namespace vkdr
