#pragma once
#include <string>
#include <vector>

#include "vk/vulkan.h"

namespace vkdr {

// The feature chain vkdiffrender enables at device creation, filled with exactly the
// features it needs. Holds pointers into itself: not copyable.
struct RequiredFeatures {
    RequiredFeatures();
    RequiredFeatures(const RequiredFeatures&) = delete;
    RequiredFeatures& operator=(const RequiredFeatures&) = delete;

    VkPhysicalDeviceFeatures2 features2{};
    VkPhysicalDeviceVulkan12Features vulkan12{};
};

// Names of everything vkdiffrender needs, for `vkdiffrender info`.
std::vector<std::string> requiredFeatureNames();

// What the device lacks, one readable name each; empty when it has everything.
std::vector<std::string> missingFeatures(VkPhysicalDevice device);

}  // namespace vkdr
