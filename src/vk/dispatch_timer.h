#pragma once
#include <map>
#include <string>
#include <vector>

#include "vk/vulkan.h"

namespace vkdr {

class VulkanContext;

// GPU time of every dispatch recorded through a CommandRecorder that carries this
// timer, from timestamp queries, summed per scope and pipeline name. A timestamp
// follows each dispatch, so a dispatch's time also covers the barrier and any copy or
// fill recorded since the dispatch before it. Each timestamp waits for the work before
// it, which serialises the stages: attach a timer only when profiling. Owns its query
// pools.
class DispatchTimer {
public:
    explicit DispatchTimer(const VulkanContext& context);
    ~DispatchTimer();
    DispatchTimer(const DispatchTimer&) = delete;
    DispatchTimer& operator=(const DispatchTimer&) = delete;

    // Milliseconds by scope, then by pipeline name.
    using Milliseconds = std::map<std::string, std::map<std::string, double>>;

    // What the dispatches recorded from now on are part of ("forward", "adjoint", ...).
    void setScope(std::string scope) { scope_ = std::move(scope); }
    const Milliseconds& milliseconds() const { return milliseconds_; }
    void clear() { milliseconds_.clear(); }

    // Called by CommandRecorder: when a command buffer begins, after each dispatch, and
    // once the command buffer has completed. One command buffer at a time.
    void begin(VkCommandBuffer commands);
    void afterDispatch(VkCommandBuffer commands, const std::string& pipeline);
    void collect();

private:
    struct Label {
        std::string scope, pipeline;
    };
    void writeTimestamp(VkCommandBuffer commands);

    VkDevice device_;
    double nanosecondsPerTick_;
    uint64_t validMask_;  // the queue's timestampValidBits as a mask
    std::vector<VkQueryPool> pools_;
    uint32_t written_ = 0;        // timestamps in the command buffer being recorded
    std::vector<Label> labels_;   // labels_[i]: the dispatch between timestamps i and i + 1
    std::string scope_;
    Milliseconds milliseconds_;
};

}  // namespace vkdr
