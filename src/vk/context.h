#pragma once
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vk/allocation_counter.h"
#include "vk/command_slots.h"
#include "vk/device_description.h"
#include "vk/vulkan.h"
#include "vk/vulkan_handle.h"

namespace vkdr {

class Buffer;
enum class MemoryUse;

struct ContextOptions {
    // Empty: prefer a discrete GPU, then integrated, then anything else usable (lavapipe).
    // Otherwise a device index as listed by `vkdiffrender info`, or part of its name
    // (deviceNamedBy, vk/device_selection.h).
    std::string device;
};

// The Khronos validation layer is on when the environment variable VKDR_VALIDATION is
// "1" (with synchronization validation) or "gpu" (GPU-assisted validation as well, which
// catches out-of-bounds accesses lavapipe would hide).
enum class ValidationMode { Off, Standard, GpuAssisted };
ValidationMode validationModeFromEnvironment();

// Instance, device and the one compute queue everything runs on.
class VulkanContext {
public:
    explicit VulkanContext(const ContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_.get(); }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_.get(); }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const DeviceDescription& description() const { return description_; }
    const std::vector<DeviceDescription>& allDevices() const { return allDevices_; }
    ValidationMode validation() const { return validation_; }
    // Number of validation-layer messages (warnings and errors) seen so far.
    uint32_t validationMessageCount() const { return validationMessages_.load(); }
    // The first allowed memory type with the `required` properties, one that also has the
    // `preferred` ones if there is such.
    uint32_t memoryTypeIndex(uint32_t allowedTypes, VkMemoryPropertyFlags required,
                             VkMemoryPropertyFlags preferred = 0) const;
    uint64_t deviceLocalHeapBytes() const;
    // Device memory held by this context's buffers (Buffer reports to it).
    AllocationCounter& allocations() const { return allocations_; }
    // What the driver says the process uses of the device-local heaps, where it supports
    // VK_EXT_memory_budget; nothing otherwise.
    std::optional<uint64_t> deviceLocalHeapUsage() const;
    void setDebugName(VkObjectType type, uint64_t handle, const std::string& name) const;

    // Command pools, buffers and fences for CommandRecorder to reuse.
    CommandSlots& commandSlots() const { return *commandSlots_; }
    // A host-visible buffer of at least `bytes` for uploads (MemoryUse::Upload) or
    // read-backs (MemoryUse::Readback), kept for the next transfer: on a GPU, allocating
    // one costs more than a small transfer itself. Valid until the next call with the
    // same use.
    const Buffer& keptStagingBuffer(MemoryUse use, VkDeviceSize bytes) const;
    // Frees the kept staging buffers, so that a measurement of the memory one renderer
    // holds (bench) does not count those that renderers before it left.
    void releaseKeptStagingBuffers() const;

    // Features vkdiffrender needs, in the words `info` prints.
    static std::vector<std::string> requiredFeatures();

private:
    void createInstance();
    void createDevice();

    // Members are destroyed in reverse order: what the device made, the device, the
    // messenger, the instance; a constructor that throws part-way releases the same way.
    ValidationMode validation_;
    std::atomic<uint32_t> validationMessages_{0};
    mutable AllocationCounter allocations_;
    InstanceHandle instance_;
    MessengerHandle messenger_;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    DeviceHandle device_;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    DeviceDescription description_;
    std::vector<DeviceDescription> allDevices_;
    std::unique_ptr<CommandSlots> commandSlots_;
    mutable std::unique_ptr<Buffer> uploadStaging_, readbackStaging_;
    bool memoryBudget_ = false;  // VK_EXT_memory_budget enabled
};

// Throws vkdr::Error when the validation layer reported anything: with VKDR_VALIDATION
// set, a validation message is a failure.
void requireNoValidationMessages(const VulkanContext& context);

}  // namespace vkdr
