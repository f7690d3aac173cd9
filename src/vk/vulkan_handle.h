#pragma once
#include <cstddef>
#include <type_traits>
#include <utility>

#include "vk/vulkan.h"

namespace vkdr {

// Owns one Vulkan object and destroys it with `*Destroy` when it goes: a constructor that
// throws part-way releases what it had made, and a moved-from owner holds nothing.
// `Parent` is the object it was made from (VkDevice, VkInstance), or std::nullptr_t for
// the instance and the device themselves. `Destroy` points at the entry point, which
// volk loads at run time.
template <typename Parent, typename Handle, auto* Destroy>
class VulkanHandle {
public:
    VulkanHandle() = default;
    explicit VulkanHandle(Handle handle) requires std::is_same_v<Parent, std::nullptr_t> : handle_(handle) {}
    VulkanHandle(Parent parent, Handle handle) : parent_(parent), handle_(handle) {}
    ~VulkanHandle() { reset(); }
    VulkanHandle(VulkanHandle&& other) noexcept
        : parent_(other.parent_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
    VulkanHandle& operator=(VulkanHandle&& other) noexcept {
        if (this != &other) {
            reset();
            parent_ = other.parent_;
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    VulkanHandle(const VulkanHandle&) = delete;
    VulkanHandle& operator=(const VulkanHandle&) = delete;

    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

    void reset() {
        if (handle_ == VK_NULL_HANDLE) {
            return;
        }
        if constexpr (std::is_same_v<Parent, std::nullptr_t>) {
            (*Destroy)(handle_, nullptr);
        } else {
            (*Destroy)(parent_, handle_, nullptr);
        }
        handle_ = VK_NULL_HANDLE;
    }

private:
    Parent parent_{};
    Handle handle_ = VK_NULL_HANDLE;
};

using InstanceHandle = VulkanHandle<std::nullptr_t, VkInstance, &vkDestroyInstance>;
using MessengerHandle = VulkanHandle<VkInstance, VkDebugUtilsMessengerEXT, &vkDestroyDebugUtilsMessengerEXT>;
using DeviceHandle = VulkanHandle<std::nullptr_t, VkDevice, &vkDestroyDevice>;
using BufferHandle = VulkanHandle<VkDevice, VkBuffer, &vkDestroyBuffer>;
using MemoryHandle = VulkanHandle<VkDevice, VkDeviceMemory, &vkFreeMemory>;
using ShaderModuleHandle = VulkanHandle<VkDevice, VkShaderModule, &vkDestroyShaderModule>;
using PipelineLayoutHandle = VulkanHandle<VkDevice, VkPipelineLayout, &vkDestroyPipelineLayout>;
using PipelineHandle = VulkanHandle<VkDevice, VkPipeline, &vkDestroyPipeline>;

}  // namespace vkdr
