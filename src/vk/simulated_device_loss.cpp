#include "vk/simulated_device_loss.h"

#include <atomic>
#include <cstdint>
#include <cstdlib>

namespace vkdr {

bool deviceLossSimulated() {
    static const uint64_t lostAt = [] {
        const char* value = std::getenv("VKDR_SIMULATE_DEVICE_LOST");
        return value ? std::strtoull(value, nullptr, 10) : 0;
    }();
    static std::atomic<uint64_t> submissions{0};
    return lostAt > 0 && ++submissions >= lostAt;
}

}  // namespace vkdr
