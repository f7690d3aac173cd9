#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vkdr {

// One Vulkan device as `vkdiffrender info` lists it.
struct DeviceDescription {
    uint32_t index = 0;
    std::string name;
    std::string driver;       // driver name and version info
    std::string type;         // "discrete GPU", "integrated GPU", "CPU", ...
    std::string apiVersion;
    std::vector<std::string> missingFeatures;  // empty: usable by vkdiffrender
};

}  // namespace vkdr
