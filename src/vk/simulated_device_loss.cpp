#include "vk/simulated_device_loss.h"

#include <atomic>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"

namespace vkdr {
namespace {

// The queue submission VKDR_SIMULATE_DEVICE_LOST names, 0 when unset; anything but a
// positive integer is refused rather than ignored, so a test that sets it cannot pass
// by never losing the device.
uint64_t submissionToLose() {
    const char* value = std::getenv("VKDR_SIMULATE_DEVICE_LOST");
    if (value == nullptr) return 0;
    const std::string text = value;
    uint64_t submission = 0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), submission);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || submission == 0) {
        throw Error("VKDR_SIMULATE_DEVICE_LOST=" + text + ": expected a positive integer, the queue submission to fail");
    }
    return submission;
}

}  // namespace

bool deviceLossSimulated() {
    static const uint64_t lostAt = submissionToLose();
    static std::atomic<uint64_t> submissions{0};
    return lostAt > 0 && ++submissions >= lostAt;
}

}  // namespace vkdr
