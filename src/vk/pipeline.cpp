#include "vk/pipeline.h"

#include "vk/context.h"
#include "vk/specialized_spirv.h"

namespace vkdr {

ComputePipeline::ComputePipeline(const VulkanContext& context, const std::string& name,
                                 std::span<const uint32_t> spirv, uint32_t pushConstantBytes,
                                 const std::vector<uint32_t>& specialization)
    : pushConstantBytes_(pushConstantBytes), name_(name) {
    const VkDevice device = context.device();
    std::vector<uint32_t> specialized;
    if (!specialization.empty()) {
        specialized = specializedSpirv(name, spirv, specialization);
        spirv = specialized;
    }
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size_bytes();
    moduleInfo.pCode = spirv.data();
    VkShaderModule rawModule;
    checkVk(vkCreateShaderModule(device, &moduleInfo, nullptr, &rawModule), ("creating shader " + name).c_str());
    // Needed only until the pipeline is made.
    const ShaderModuleHandle module(device, rawModule);

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VkPipelineLayout layout;
    checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
    layout_ = PipelineLayoutHandle(device, layout);

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.get();
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline;
    checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
            ("creating pipeline " + name).c_str());
    pipeline_ = PipelineHandle(device, pipeline);
    context.setDebugName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), name);
}

}  // namespace vkdr
