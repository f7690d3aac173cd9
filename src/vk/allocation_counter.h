#pragma once
#include <atomic>
#include <cstdint>

namespace vkdr {

// Device memory the process holds through its own allocations: now, and the most held
// at any one time since the last resetPeak().
class AllocationCounter {
public:
    void add(uint64_t bytes) {
        uint64_t now = current_.fetch_add(bytes) + bytes;
        uint64_t peak = peak_.load();
        while (now > peak && !peak_.compare_exchange_weak(peak, now)) {
        }
    }
    void remove(uint64_t bytes) { current_.fetch_sub(bytes); }
    uint64_t current() const { return current_.load(); }
    uint64_t peak() const { return peak_.load(); }
    void resetPeak() { peak_.store(current_.load()); }

private:
    std::atomic<uint64_t> current_{0};
    std::atomic<uint64_t> peak_{0};
};

}  // namespace vkdr
