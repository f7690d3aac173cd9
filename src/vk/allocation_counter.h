#pragma once
#include <atomic>
#include <cstdint>
#include <utility>

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

// Counts `bytes` in a counter for as long as it lives. Move-only owner of the count.
class CountedBytes {
public:
    CountedBytes() = default;
    CountedBytes(AllocationCounter& counter, uint64_t bytes) : counter_(&counter), bytes_(bytes) { counter.add(bytes); }
    ~CountedBytes() { reset(); }
    CountedBytes(CountedBytes&& other) noexcept
        : counter_(std::exchange(other.counter_, nullptr)), bytes_(std::exchange(other.bytes_, 0)) {}
    CountedBytes& operator=(CountedBytes&& other) noexcept {
        if (this != &other) {
            reset();
            counter_ = std::exchange(other.counter_, nullptr);
            bytes_ = std::exchange(other.bytes_, 0);
        }
        return *this;
    }
    CountedBytes(const CountedBytes&) = delete;
    CountedBytes& operator=(const CountedBytes&) = delete;

    void reset() {
        if (counter_ != nullptr) {
            counter_->remove(bytes_);
        }
        counter_ = nullptr;
        bytes_ = 0;
    }

private:
    AllocationCounter* counter_ = nullptr;
    uint64_t bytes_ = 0;
};

}  // namespace vkdr
