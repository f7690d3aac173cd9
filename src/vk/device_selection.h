#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "vk/device_description.h"

namespace vkdr {

// The device `--device request` names. A string of digits is an index into `devices`
// and nothing else, so "1" never picks a device whose name happens to contain a 1;
// anything else picks the first device whose name contains it. Throws vkdr::Error
// naming every device when none matches.
uint32_t deviceNamedBy(const std::string& request, const std::vector<DeviceDescription>& devices);

}  // namespace vkdr
