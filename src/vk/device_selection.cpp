#include "vk/device_selection.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "core/setting_names.h"

namespace vkdr {
namespace {

bool isIndex(const std::string& request) {
    return !request.empty() &&
           std::all_of(request.begin(), request.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

[[noreturn]] void throwNoSuchDevice(const std::string& request, const std::string& reason,
                                    const std::vector<DeviceDescription>& devices) {
    std::string list;
    for (const DeviceDescription& d : devices) {
        list += (list.empty() ? " [" : "; [") + std::to_string(d.index) + "] " + d.name;
    }
    throw Error(settingName(Setting::Device) + " " + request + ": " + reason + "; the devices are:" + list);
}

}  // namespace

uint32_t deviceNamedBy(const std::string& request, const std::vector<DeviceDescription>& devices) {
    if (isIndex(request)) {
        // Compared as text, so that digits too many for any integer type are simply out of range.
        const std::string digits = request.substr(std::min(request.find_first_not_of('0'), request.size() - 1));
        for (uint32_t i = 0; i < devices.size(); ++i) {
            if (digits == std::to_string(i)) {
                return i;
            }
        }
        throwNoSuchDevice(request, "no device has that index", devices);
    }
    for (uint32_t i = 0; i < devices.size(); ++i) {
        if (devices[i].name.find(request) != std::string::npos) {
            return i;
        }
    }
    throwNoSuchDevice(request, "no device's name contains '" + request + "'", devices);
}

}  // namespace vkdr
