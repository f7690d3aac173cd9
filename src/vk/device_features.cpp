#include "vk/device_features.h"

#include <cstring>

namespace vkdr {

RequiredFeatures::RequiredFeatures() {
    atomicFloat.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT;
    atomicFloat.shaderBufferFloat32AtomicAdd = VK_TRUE;  // gradient accumulation
    vulkan12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    vulkan12.pNext = &atomicFloat;
    vulkan12.bufferDeviceAddress = VK_TRUE;  // every stage reads its buffers by address
    features2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    features2.pNext = &vulkan12;
}

std::vector<std::string> requiredFeatureNames() {
    return {"Vulkan 1.2",
            "bufferDeviceAddress",
            "VK_EXT_shader_atomic_float: shaderBufferFloat32AtomicAdd",
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

    uint32_t extensionCount = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &extensionCount, nullptr);
    std::vector<VkExtensionProperties> extensions(extensionCount);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &extensionCount, extensions.data());
    auto hasExtension = [&](const char* name) {
        for (const VkExtensionProperties& e : extensions) {
            if (std::strcmp(e.extensionName, name) == 0) {
                return true;
            }
        }
        return false;
    };

    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomicFloat{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    vulkan12.pNext = &atomicFloat;
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &vulkan12;
    vkGetPhysicalDeviceFeatures2(device, &features2);
    if (!vulkan12.bufferDeviceAddress) {
        missing.push_back("bufferDeviceAddress");
    }
    if (!hasExtension(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME) || !atomicFloat.shaderBufferFloat32AtomicAdd) {
        missing.push_back("VK_EXT_shader_atomic_float: shaderBufferFloat32AtomicAdd");
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
