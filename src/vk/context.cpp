#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/setting_names.h"
#include "vk/buffer.h"
#include "vk/device_features.h"
#include "vk/device_selection.h"

namespace vkdr {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* userData) {
    auto* count = static_cast<std::atomic<uint32_t>*>(userData);
    count->fetch_add(1);
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    std::fprintf(stderr, "vulkan validation %s: %s\n", level, data->pMessage);
    return VK_FALSE;
}

std::string deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

int typePreference(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

std::string versionText(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

bool hasComputeQueue(VkPhysicalDevice device, uint32_t* family) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) {
            *family = i;
            return true;
        }
    }
    return false;
}

DeviceDescription describe(VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &properties);
    DeviceDescription d;
    d.index = index;
    d.name = properties.properties.deviceName;
    d.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    d.type = deviceTypeName(properties.properties.deviceType);
    d.apiVersion = versionText(properties.properties.apiVersion);
    d.missingFeatures = missingFeatures(device);
    uint32_t family;
    if (!hasComputeQueue(device, &family)) {
        d.missingFeatures.push_back("a compute queue with timestamps");
    }
    return d;
}

bool supportsExtension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
                       [name](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}
}  // namespace

ValidationMode validationModeFromEnvironment() {
    const char* value = std::getenv("VKDR_VALIDATION");
    if (value == nullptr || std::strcmp(value, "") == 0 || std::strcmp(value, "0") == 0) {
        return ValidationMode::Off;
    }
    if (std::strcmp(value, "gpu") == 0) {
        return ValidationMode::GpuAssisted;
    }
    return ValidationMode::Standard;
}

std::vector<std::string> VulkanContext::requiredFeatures() {
    return requiredFeatureNames();
}

VulkanContext::VulkanContext(const ContextOptions& options) : validation_(validationModeFromEnvironment()) {
    if (volkInitialize() != VK_SUCCESS) {
        throw Error("no Vulkan loader found (install libvulkan1 and a driver, e.g. mesa-vulkan-drivers for lavapipe)");
    }
    createInstance();

    uint32_t count = 0;
    checkVk(vkEnumeratePhysicalDevices(instance(), &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    checkVk(vkEnumeratePhysicalDevices(instance(), &count, devices.data()), "vkEnumeratePhysicalDevices");
    if (count == 0) {
        throw Error("no Vulkan device found (install mesa-vulkan-drivers for the CPU device lavapipe)");
    }
    for (uint32_t i = 0; i < count; ++i) {
        allDevices_.push_back(describe(devices[i], i));
    }

    int chosen = -1;
    if (options.device.empty()) {
        int best = 1 << 30;
        for (uint32_t i = 0; i < count; ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            if (allDevices_[i].missingFeatures.empty() && typePreference(p.deviceType) < best) {
                best = typePreference(p.deviceType);
                chosen = static_cast<int>(i);
            }
        }
        if (chosen < 0) {
            std::string message = "no Vulkan device has the features vkdiffrender needs:";
            for (const DeviceDescription& d : allDevices_) {
                message += "\n  " + d.name + " lacks:";
                for (const std::string& f : d.missingFeatures) {
                    message += " " + f + ";";
                }
            }
            throw Error(message);
        }
    } else {
        chosen = static_cast<int>(deviceNamedBy(options.device, allDevices_));
        const DeviceDescription& d = allDevices_[chosen];
        if (!d.missingFeatures.empty()) {
            std::string message = settingName(Setting::Device) + " " + options.device + ": " + d.name + " lacks:";
            for (const std::string& f : d.missingFeatures) {
                message += " " + f + ";";
            }
            throw Error(message);
        }
    }
    physicalDevice_ = devices[chosen];
    description_ = allDevices_[chosen];
    hasComputeQueue(physicalDevice_, &queueFamily_);  // it has one: it lacks nothing
    vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
    createDevice();
}

void VulkanContext::createInstance() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vkdiffrender";
    app.apiVersion = VK_API_VERSION_1_2;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    std::vector<VkValidationFeatureEnableEXT> enables;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidationMessage;
    messengerInfo.pUserData = &validationMessages_;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation_ != ValidationMode::Off) {
        uint32_t count = 0;
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> available(count);
        vkEnumerateInstanceLayerProperties(&count, available.data());
        bool found = std::any_of(available.begin(), available.end(), [](const VkLayerProperties& l) {
            return std::strcmp(l.layerName, kValidationLayer) == 0;
        });
        if (!found) {
            throw Error("VKDR_VALIDATION is set but the Khronos validation layer is not installed "
                        "(apt-get install vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        enables.push_back(VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT);
        if (validation_ == ValidationMode::GpuAssisted) {
            enables.push_back(VK_VALIDATION_FEATURE_ENABLE_GPU_ASSISTED_EXT);
        }
        features.enabledValidationFeatureCount = static_cast<uint32_t>(enables.size());
        features.pEnabledValidationFeatures = enables.data();
        features.pNext = &messengerInfo;
        info.pNext = &features;
    }
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance;
    const VkResult created = vkCreateInstance(&info, nullptr, &instance);
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER) {
        throw Error("no Vulkan driver found (install mesa-vulkan-drivers for the CPU device lavapipe)");
    }
    checkVk(created, "vkCreateInstance");
    instance_ = InstanceHandle(instance);
    volkLoadInstanceOnly(instance);
    if (validation_ != ValidationMode::Off) {
        VkDebugUtilsMessengerEXT messenger;
        checkVk(vkCreateDebugUtilsMessengerEXT(instance, &messengerInfo, nullptr, &messenger),
                "vkCreateDebugUtilsMessengerEXT");
        messenger_ = MessengerHandle(instance, messenger);
    }
}

void VulkanContext::createDevice() {
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    RequiredFeatures features;
    std::vector<const char*> extensions;
    // Optional: lets the benchmark report the driver's own count of memory in use.
    memoryBudget_ = supportsExtension(physicalDevice_, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    if (memoryBudget_) {
        extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    }
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features.features2;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkDevice device;
    checkVk(vkCreateDevice(physicalDevice_, &info, nullptr, &device), "vkCreateDevice");
    device_ = DeviceHandle(device);
    volkLoadDevice(device);
    vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
    commandSlots_ = std::make_unique<CommandSlots>(device, queueFamily_);
}

VulkanContext::~VulkanContext() {
    if (device_) {
        vkDeviceWaitIdle(device_.get());
    }
}

const Buffer& VulkanContext::keptStagingBuffer(MemoryUse use, VkDeviceSize bytes) const {
    std::unique_ptr<Buffer>& staging = use == MemoryUse::Upload ? uploadStaging_ : readbackStaging_;
    if (!staging || staging->size() < bytes) {
        staging.reset();  // before allocating its successor: peak memory holds one
        staging = std::make_unique<Buffer>(*this, bytes, use,
                                           use == MemoryUse::Upload ? "upload staging" : "readback staging");
    }
    return *staging;
}

void VulkanContext::releaseKeptStagingBuffers() const {
    uploadStaging_.reset();
    readbackStaging_.reset();
}

uint32_t VulkanContext::memoryTypeIndex(uint32_t allowedTypes, VkMemoryPropertyFlags required,
                                        VkMemoryPropertyFlags preferred) const {
    for (VkMemoryPropertyFlags wanted : {required | preferred, required}) {
        for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
            if ((allowedTypes & (1u << i)) && (memoryProperties_.memoryTypes[i].propertyFlags & wanted) == wanted) {
                return i;
            }
        }
    }
    throw Error("the device has no memory type with the needed properties");
}

uint64_t VulkanContext::deviceLocalHeapBytes() const {
    uint64_t largest = 0;
    for (uint32_t i = 0; i < memoryProperties_.memoryHeapCount; ++i) {
        if (memoryProperties_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
            largest = std::max<uint64_t>(largest, memoryProperties_.memoryHeaps[i].size);
        }
    }
    return largest;
}

std::optional<uint64_t> VulkanContext::deviceLocalHeapUsage() const {
    if (!memoryBudget_) {
        return std::nullopt;
    }
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    properties.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(physicalDevice_, &properties);
    uint64_t used = 0;
    for (uint32_t i = 0; i < properties.memoryProperties.memoryHeapCount; ++i) {
        if (properties.memoryProperties.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
            used += budget.heapUsage[i];
        }
    }
    return used;
}

void VulkanContext::setDebugName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!messenger_) {
        return;
    }
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    vkSetDebugUtilsObjectNameEXT(device(), &info);
}

void requireNoValidationMessages(const VulkanContext& context) {
    if (context.validationMessageCount() > 0) {
        throw Error("the Vulkan validation layer reported " + std::to_string(context.validationMessageCount()) +
                    " message(s) (printed above)");
    }
}

}  // namespace vkdr
