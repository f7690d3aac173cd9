#include "vk/buffer.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "vk/commands.h"
#include "vk/context.h"

namespace vkdr {

namespace {

// Sizes are rounded up: the Debian 12 validation layers (1.3.239) report false
// out-of-bounds errors under GPU-assisted validation for loads from buffers only a
// struct or two long (fixed upstream in 1.3.280).
constexpr VkDeviceSize kSizeGranularity = 256;

VkDeviceSize paddedSize(VkDeviceSize size) {
    return (std::max<VkDeviceSize>(size, 1) + kSizeGranularity - 1) / kSizeGranularity * kSizeGranularity;
}

// Transfers of up to this size (parameters, losses, gradients, small films) come every
// iteration and share the context's kept staging buffers; a larger one gets a buffer of
// its own, freed after it, so that no scene-sized staging buffer outlives its upload.
constexpr VkDeviceSize kKeptStagingBytes = VkDeviceSize(4) << 20;

// The host-visible buffer one transfer goes through.
class Staging {
public:
    Staging(const VulkanContext& context, MemoryUse use, VkDeviceSize bytes, const std::string& name) {
        if (bytes <= kKeptStagingBytes) {
            kept_ = &context.keptStagingBuffer(use, bytes);
        } else {
            owned_ = Buffer(context, bytes, use, name);
        }
    }
    const Buffer& buffer() const { return kept_ ? *kept_ : owned_; }

private:
    const Buffer* kept_ = nullptr;
    Buffer owned_;
};

}  // namespace

Buffer::Buffer(const VulkanContext& context, VkDeviceSize size, MemoryUse use, const std::string& name)
    : size_(paddedSize(size)) {
    const VkDevice device = context.device();
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size_;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer;
    checkVk(vkCreateBuffer(device, &info, nullptr, &buffer), ("creating buffer " + name).c_str());
    buffer_ = BufferHandle(device, buffer);
    context.setDebugName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buffer), name);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer, &requirements);
    VkMemoryPropertyFlags properties = use == MemoryUse::Device
                                           ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                           : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.pNext = &flags;
    allocation.allocationSize = requirements.size;
    allocation.memoryTypeIndex = context.memoryTypeIndex(
        requirements.memoryTypeBits, properties, use == MemoryUse::Readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0);
    VkDeviceMemory memory;
    checkVk(vkAllocateMemory(device, &allocation, nullptr, &memory),
            ("allocating " + std::to_string(size_ >> 20) + " MiB for " + name).c_str());
    memory_ = MemoryHandle(device, memory);
    counted_ = CountedBytes(context.allocations(), requirements.size);
    checkVk(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    if (use != MemoryUse::Device) {
        checkVk(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    }
    VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addressInfo.buffer = buffer;
    address_ = vkGetBufferDeviceAddress(device, &addressInfo);
}

Buffer::~Buffer() {
    release();
}

Buffer::Buffer(Buffer&& other) noexcept {
    *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        counted_ = std::move(other.counted_);
        memory_ = std::move(other.memory_);
        buffer_ = std::move(other.buffer_);
        size_ = std::exchange(other.size_, 0);
        address_ = std::exchange(other.address_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void Buffer::release() {
    buffer_.reset();
    memory_.reset();
    counted_.reset();
    mapped_ = nullptr;
}

Buffer uploadBuffer(const VulkanContext& context, std::span<const std::byte> bytes, const std::string& name) {
    Buffer buffer;
    overwriteBuffer(context, buffer, bytes, name);
    return buffer;
}

void overwriteBuffer(const VulkanContext& context, Buffer& buffer, std::span<const std::byte> bytes,
                     const std::string& name) {
    overwriteBuffer(context, buffer, std::span(&bytes, 1), name);
}

void overwriteBuffer(const VulkanContext& context, Buffer& buffer,
                     std::span<const std::span<const std::byte>> parts, const std::string& name) {
    size_t total = 0;
    for (std::span<const std::byte> part : parts) total += part.size();
    if (buffer.size() != paddedSize(total)) {
        buffer = Buffer(context, total, MemoryUse::Device, name);
    }
    // The parts, then zeros up to the padded size.
    Staging transfer(context, MemoryUse::Upload, buffer.size(), name + " (staging)");
    std::byte* staged = static_cast<std::byte*>(transfer.buffer().mapped());
    for (std::span<const std::byte> part : parts) {
        if (!part.empty()) std::memcpy(staged, part.data(), part.size());
        staged += part.size();
    }
    std::memset(staged, 0, buffer.size() - total);
    CommandRecorder recorder(context);
    recorder.copy(transfer.buffer(), buffer, buffer.size());
    recorder.submitAndWait();
}

void downloadBuffer(const VulkanContext& context, const Buffer& buffer, std::span<std::byte> bytes) {
    downloadBuffers(context, {{&buffer, bytes}});
}

void downloadBuffers(const VulkanContext& context, std::span<const Download> downloads) {
    VkDeviceSize total = 0;
    for (const Download& d : downloads) {
        total += d.bytes.size();
    }
    Staging transfer(context, MemoryUse::Readback, total, "readback");
    const Buffer& readback = transfer.buffer();
    CommandRecorder recorder(context);
    VkDeviceSize offset = 0;
    for (const Download& d : downloads) {
        if (!d.bytes.empty()) {
            recorder.copyRange(*d.buffer, 0, readback, offset, d.bytes.size());
        }
        offset += d.bytes.size();
    }
    recorder.submitAndWait();
    offset = 0;
    for (const Download& d : downloads) {
        if (!d.bytes.empty()) {
            std::memcpy(d.bytes.data(), static_cast<const std::byte*>(readback.mapped()) + offset, d.bytes.size());
        }
        offset += d.bytes.size();
    }
}

}  // namespace vkdr
