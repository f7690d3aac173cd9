#pragma once
#include <cstdint>
#include <mutex>
#include <vector>

#include "vk/vulkan.h"

namespace vkdr {

// What one CommandRecorder records into and waits on.
struct CommandSlot {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

// Command slots kept for reuse: on a GPU, creating and destroying a pool and a fence for
// every recorder costs more than the small submissions of a gradient iteration at low
// resolution spend on the device (docs/performance.md).
class CommandSlots {
public:
    CommandSlots(VkDevice device, uint32_t queueFamily);
    ~CommandSlots();
    CommandSlots(const CommandSlots&) = delete;
    CommandSlots& operator=(const CommandSlots&) = delete;

    // An idle slot (its command buffer reset, its fence unsignalled), or a new one.
    CommandSlot acquire();
    // Takes back a slot whose commands are not pending and whose fence is unsignalled.
    void release(CommandSlot slot);
    // For a slot that cannot be reused (its submission failed).
    void destroy(CommandSlot slot) const;

private:
    VkDevice device_;
    uint32_t queueFamily_;
    std::mutex mutex_;
    std::vector<CommandSlot> idle_;
};

}  // namespace vkdr
