#include "vk/commands.h"

#include <cassert>

#include "core/error.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/dispatch_timer.h"
#include "vk/pipeline.h"
#include "vk/simulated_device_loss.h"

namespace vkdr {

constexpr uint32_t kMaxWorkgroups = kMaxDispatchThreads / kWorkgroupSize;

CommandRecorder::CommandRecorder(const VulkanContext& context, DispatchTimer* timer)
    : context_(context), timer_(timer), slot_(context.commandSlots().acquire()), commands_(slot_.commands) {
    try {
        begin();
    } catch (...) {
        context_.commandSlots().destroy(slot_);
        throw;
    }
}

CommandRecorder::~CommandRecorder() {
    if (reusable_) {
        context_.commandSlots().release(slot_);
    } else {
        context_.commandSlots().destroy(slot_);
    }
}

void CommandRecorder::begin() {
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(commands_, &info), "vkBeginCommandBuffer");
    if (timer_) {
        timer_->begin(commands_);
    }
}

void CommandRecorder::copy(const Buffer& from, const Buffer& to, VkDeviceSize bytes) {
    copyRange(from, 0, to, 0, bytes);
}

void CommandRecorder::copyRange(const Buffer& from, VkDeviceSize fromOffset, const Buffer& to, VkDeviceSize toOffset,
                                VkDeviceSize bytes) {
    VkBufferCopy region{fromOffset, toOffset, bytes};
    vkCmdCopyBuffer(commands_, from.handle(), to.handle(), 1, &region);
}

void CommandRecorder::fill(const Buffer& buffer, uint32_t value) {
    vkCmdFillBuffer(commands_, buffer.handle(), 0, VK_WHOLE_SIZE, value);
}

void CommandRecorder::fillRange(const Buffer& buffer, VkDeviceSize offset, VkDeviceSize bytes, uint32_t value) {
    vkCmdFillBuffer(commands_, buffer.handle(), offset, bytes, value);
}

void CommandRecorder::bind(const ComputePipeline& pipeline, std::span<const std::byte> pushConstants) {
    assert(pushConstants.size() == pipeline.pushConstantBytes());
    vkCmdBindPipeline(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    vkCmdPushConstants(commands_, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       static_cast<uint32_t>(pushConstants.size()), pushConstants.data());
}

void CommandRecorder::dispatch(const ComputePipeline& pipeline, uint32_t threads,
                               std::span<const std::byte> pushConstants) {
    uint32_t groups = (threads + kWorkgroupSize - 1) / kWorkgroupSize;
    if (groups > kMaxWorkgroups) {
        throw Error("internal: dispatch of " + std::to_string(threads) + " threads exceeds the workgroup limit");
    }
    if (groups == 0) {
        return;
    }
    bind(pipeline, pushConstants);
    vkCmdDispatch(commands_, groups, 1, 1);
    if (timer_) {
        timer_->afterDispatch(commands_, pipeline.name());
    }
}

void CommandRecorder::dispatchIndirect(const ComputePipeline& pipeline, const Buffer& args, VkDeviceSize offset,
                                       std::span<const std::byte> pushConstants) {
    bind(pipeline, pushConstants);
    vkCmdDispatchIndirect(commands_, args.handle(), offset);
    if (timer_) {
        timer_->afterDispatch(commands_, pipeline.name());
    }
}

void CommandRecorder::barrier() {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                            VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                             VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void CommandRecorder::submitAndWait() {
    // The fence wait below orders this submission before the host's next step and
    // before later submissions, but does not make the device's writes visible to them:
    // this barrier does, for read-backs and for whatever is submitted next.
    VkMemoryBarrier handOver{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    handOver.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    handOver.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &handOver, 0, nullptr,
                         0, nullptr);
    checkVk(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    // Until the fence is reset, a failure leaves the slot in a state not worth reusing.
    reusable_ = false;
    VkResult submitted =
        deviceLossSimulated() ? VK_ERROR_DEVICE_LOST : vkQueueSubmit(context_.queue(), 1, &submit, slot_.fence);
    checkVk(submitted, "vkQueueSubmit");
    checkVk(vkWaitForFences(context_.device(), 1, &slot_.fence, VK_TRUE, UINT64_MAX), "waiting for the device");
    checkVk(vkResetFences(context_.device(), 1, &slot_.fence), "vkResetFences");
    reusable_ = true;
    if (timer_) {
        timer_->collect();
    }
    checkVk(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    begin();
}

}  // namespace vkdr
