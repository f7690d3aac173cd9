#pragma once
// Vulkan through volk: entry points are loaded at run time, nothing links libvulkan.
#include <volk.h>

#include <string>

#include "core/error.h"

namespace vkdr {

// The device stopped working (VK_ERROR_DEVICE_LOST): a GPU reset, a driver's watchdog.
// The input may well be fine, and an optimisation can resume from its last checkpoint.
class DeviceLostError : public Error {
public:
    using Error::Error;
};

// Throws vkdr::Error for a failed call (DeviceLostError for a lost device); device loss
// and out-of-memory get messages a user can act on.
void checkVk(VkResult result, const char* what);

std::string vkResultName(VkResult result);

}  // namespace vkdr
