#include "vk/command_slots.h"

namespace vkdr {

CommandSlots::CommandSlots(VkDevice device, uint32_t queueFamily) : device_(device), queueFamily_(queueFamily) {}

CommandSlots::~CommandSlots() {
    for (const CommandSlot& slot : idle_) {
        destroy(slot);
    }
}

CommandSlot CommandSlots::acquire() {
    {
        std::lock_guard lock(mutex_);
        if (!idle_.empty()) {
            CommandSlot slot = idle_.back();
            idle_.pop_back();
            return slot;
        }
    }
    CommandSlot slot;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily_;
    checkVk(vkCreateCommandPool(device_, &poolInfo, nullptr, &slot.pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocation.commandPool = slot.pool;
    allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocation.commandBufferCount = 1;
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkResult allocated = vkAllocateCommandBuffers(device_, &allocation, &slot.commands);
    VkResult created = allocated == VK_SUCCESS ? vkCreateFence(device_, &fenceInfo, nullptr, &slot.fence) : allocated;
    if (created != VK_SUCCESS) {
        destroy(slot);
        checkVk(created, "creating a command buffer and its fence");
    }
    return slot;
}

void CommandSlots::release(CommandSlot slot) {
    VkResult reset = vkResetCommandPool(device_, slot.pool, 0);
    if (reset != VK_SUCCESS) {
        destroy(slot);
        return;
    }
    std::lock_guard lock(mutex_);
    idle_.push_back(slot);
}

void CommandSlots::destroy(CommandSlot slot) const {
    vkDestroyFence(device_, slot.fence, nullptr);
    vkDestroyCommandPool(device_, slot.pool, nullptr);
}

}  // namespace vkdr
