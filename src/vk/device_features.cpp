#include "vk/device_features.h"

namespace vkdr {

RequiredFeatures::RequiredFeatures() {
    vulkan12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    vulkan12.bufferDeviceAddress = VK_TRUE;  // every stage reads its buffers by address
    // Gradients and the loss are fixed-point sums of 64-bit words (shaders/lib/fixed_point.glsl).
    vulkan12.shaderBufferInt64Atomics = VK_TRUE;
    vulkan12.shaderSubgroupExtendedTypes = VK_TRUE;
    features2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    features2.features.shaderInt64 = VK_TRUE;
    features2.pNext = &vulkan12;
}

std::vector<std::string> requiredFeatureNames() {
    return {"Vulkan 1.2",
            "bufferDeviceAddress",
            "shaderInt64",
            "shaderBufferInt64Atomics",
            "shaderSubgroupExtendedTypes",
            "compute-stage subgroup operations: basic, ballot, arithmetic",
            "timestampComputeAndGraphics"};
}

std::vector<std::string> missingFeatures(VkPhysicalDevice device) {
    std::vector<std::string> missing;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (properties.apiVersion < VK_API_VERSION_1_2) {
        return {"Vulkan 1.2"};
    }

    VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &vulkan12;
    vkGetPhysicalDeviceFeatures2(device, &features2);
    if (!vulkan12.bufferDeviceAddress) {
        missing.push_back("bufferDeviceAddress");
    }
    if (!features2.features.shaderInt64) {
        missing.push_back("shaderInt64");
    }
    if (!vulkan12.shaderBufferInt64Atomics) {
        missing.push_back("shaderBufferInt64Atomics");
    }
    if (!vulkan12.shaderSubgroupExtendedTypes) {
        missing.push_back("shaderSubgroupExtendedTypes");
    }

    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device, &properties2);
    const VkSubgroupFeatureFlags neededOps = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT |
                                             VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) ||
        (subgroup.supportedOperations & neededOps) != neededOps) {
        missing.push_back("compute-stage subgroup operations: basic, ballot, arithmetic");
    }
    if (!properties.limits.timestampComputeAndGraphics) {
        missing.push_back("timestampComputeAndGraphics");
    }
    return missing;
}

}  // namespace vkdr
