#pragma once
// Vulkan through volk: entry points are loaded at run time, nothing links libvulkan.
#include <volk.h>

#include <string>

namespace vkdr {

// Throws vkdr::Error for a failed call; device loss and out-of-memory get messages a
// user can act on.
void checkVk(VkResult result, const char* what);

std::string vkResultName(VkResult result);

}  // namespace vkdr
