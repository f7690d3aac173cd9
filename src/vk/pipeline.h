#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vk/vulkan.h"
#include "vk/vulkan_handle.h"

namespace vkdr {

class VulkanContext;

// A compute pipeline whose only interface is a push-constant block: stages reach their
// buffers by device address, so there are no descriptor sets. Move-only owner.
class ComputePipeline {
public:
    ComputePipeline() = default;
    // `specialization[i]` is the value of constant_id i, fixed in the SPIR-V before the
    // driver sees it (specializedSpirv).
    ComputePipeline(const VulkanContext& context, const std::string& name, std::span<const uint32_t> spirv,
                    uint32_t pushConstantBytes, const std::vector<uint32_t>& specialization = {});

    VkPipeline handle() const { return pipeline_.get(); }
    VkPipelineLayout layout() const { return layout_.get(); }
    uint32_t pushConstantBytes() const { return pushConstantBytes_; }
    const std::string& name() const { return name_; }

private:
    PipelineLayoutHandle layout_;
    PipelineHandle pipeline_;  // destroyed before the layout it was made with
    uint32_t pushConstantBytes_ = 0;
    std::string name_;
};

}  // namespace vkdr
