#pragma once
#include <cstddef>
#include <initializer_list>
#include <span>
#include <string>

#include "vk/allocation_counter.h"
#include "vk/vulkan.h"
#include "vk/vulkan_handle.h"

namespace vkdr {

class VulkanContext;

enum class MemoryUse {
    Device,    // device-local; filled by transfers or shaders
    Readback,  // host-visible and coherent, and cached where the device offers it (a GPU's
               // uncached host memory is slow to read); the device copies into it for the host
    Upload,    // host-visible and coherent; the host writes, the device copies from it
};

// A buffer with its own memory allocation and device address. Move-only owner.
class Buffer {
public:
    Buffer() = default;
    Buffer(const VulkanContext& context, VkDeviceSize size, MemoryUse use, const std::string& name);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_.get(); }
    VkDeviceSize size() const { return size_; }  // at least the size asked for
    VkDeviceAddress address() const { return address_; }
    // Host pointer for Readback and Upload buffers, nullptr otherwise.
    void* mapped() const { return mapped_; }

private:
    void release();

    // Released in reverse order: the buffer, then its memory and the context's count of it.
    CountedBytes counted_;  // memory_'s size, in the context's AllocationCounter
    MemoryHandle memory_;
    BufferHandle buffer_;
    VkDeviceSize size_ = 0;
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;
};

// A device buffer holding `bytes`, uploaded through a staging buffer (empty data gives a
// small zeroed buffer, so every address is valid).
Buffer uploadBuffer(const VulkanContext& context, std::span<const std::byte> bytes, const std::string& name);

// Writes `bytes` into `buffer` in place when it has room for exactly as many (its
// address stays valid), else into a new device buffer that replaces it.
void overwriteBuffer(const VulkanContext& context, Buffer& buffer, std::span<const std::byte> bytes,
                     const std::string& name);

// overwriteBuffer() with the bytes of `parts` one after another, copied straight into the
// staging buffer (a density grid's values are not first gathered into one host array).
void overwriteBuffer(const VulkanContext& context, Buffer& buffer,
                     std::span<const std::span<const std::byte>> parts, const std::string& name);

template <typename T>
Buffer uploadVector(const VulkanContext& context, std::span<const T> values, const std::string& name) {
    return uploadBuffer(context, std::as_bytes(values), name);
}

// Copies a device buffer's first `bytes.size()` bytes to the host.
void downloadBuffer(const VulkanContext& context, const Buffer& buffer, std::span<std::byte> bytes);

// downloadBuffer() for several buffers, through one read-back buffer and one submission.
struct Download {
    const Buffer* buffer;
    std::span<std::byte> bytes;
};
void downloadBuffers(const VulkanContext& context, std::span<const Download> downloads);
inline void downloadBuffers(const VulkanContext& context, std::initializer_list<Download> downloads) {
    downloadBuffers(context, std::span<const Download>(downloads.begin(), downloads.size()));
}

}  // namespace vkdr
