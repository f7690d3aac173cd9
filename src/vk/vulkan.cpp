#include "vk/vulkan.h"

#include "core/error.h"
#include "core/setting_names.h"

namespace vkdr {

std::string vkResultName(VkResult result) {
    switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    default: return "VkResult " + std::to_string(static_cast<int>(result));
    }
}

void checkVk(VkResult result, const char* what) {
    if (result == VK_SUCCESS) {
        return;
    }
    std::string message = std::string(what) + " failed: " + vkResultName(result);
    if (result == VK_ERROR_DEVICE_LOST) {
        throw DeviceLostError(message +
                              " (the GPU driver reset the device; a very long pass can trigger its watchdog: try "
                              "fewer " + settingName(Setting::PathsPerPass) + " or a smaller image)");
    }
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
        message += " (the scene or the image does not fit in the device's memory: try a smaller image, by " +
                   imageSizeSettingNames() + " or a target of fewer pixels)";
    }
    throw Error(message);
}

}  // namespace vkdr
