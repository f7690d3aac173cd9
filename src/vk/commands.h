#pragma once
#include <cstdint>
#include <span>

#include "vk/command_slots.h"
#include "vk/vulkan.h"

namespace vkdr {

class VulkanContext;
class Buffer;
class ComputePipeline;
class DispatchTimer;

// The threads of a workgroup in every stage (gpu::kWorkgroupSize, device_types.h), and
// the most threads one dispatch may have: Vulkan guarantees at least 65535 workgroups
// per dispatch dimension.
inline constexpr uint32_t kWorkgroupSize = 64;
inline constexpr uint32_t kMaxDispatchThreads = 65535u * kWorkgroupSize;

// Records one command buffer on the compute queue and submits it. Stages are separated
// by full compute barriers: each stage reads what the previous one wrote, and buffers
// are reached by address, so finer-grained barriers would buy nothing.
class CommandRecorder {
public:
    // With a timer, every dispatch is timed (vk/dispatch_timer.h); without, nothing is added.
    explicit CommandRecorder(const VulkanContext& context, DispatchTimer* timer = nullptr);
    ~CommandRecorder();
    CommandRecorder(const CommandRecorder&) = delete;
    CommandRecorder& operator=(const CommandRecorder&) = delete;

    void copy(const Buffer& from, const Buffer& to, VkDeviceSize bytes);
    void copyRange(const Buffer& from, VkDeviceSize fromOffset, const Buffer& to, VkDeviceSize toOffset,
                   VkDeviceSize bytes);
    void fill(const Buffer& buffer, uint32_t value);
    void fillRange(const Buffer& buffer, VkDeviceSize offset, VkDeviceSize bytes, uint32_t value);
    void dispatch(const ComputePipeline& pipeline, uint32_t threads, std::span<const std::byte> pushConstants);
    // Workgroup counts come from `args` at `offset` (a VkDispatchIndirectCommand).
    void dispatchIndirect(const ComputePipeline& pipeline, const Buffer& args, VkDeviceSize offset,
                          std::span<const std::byte> pushConstants);
    // Makes every earlier write visible to every later command (shader, transfer, indirect).
    void barrier();
    // Submits, waits, and leaves the recorder ready to record again.
    void submitAndWait();

private:
    void begin();
    void bind(const ComputePipeline& pipeline, std::span<const std::byte> pushConstants);

    const VulkanContext& context_;
    DispatchTimer* timer_;
    CommandSlot slot_;  // from the context's CommandSlots, returned on destruction
    VkCommandBuffer commands_;
    bool reusable_ = true;
};

}  // namespace vkdr
