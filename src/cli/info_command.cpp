#include <cstdio>

#include "cli/commands.h"
#include "cli/number_options.h"
#include "vk/context.h"

namespace vkdr {

CommandAction addInfoCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand("info", "List the Vulkan devices, the one vkdiffrender would use, "
                                                   "and the device features it needs");
    auto options = std::make_shared<ContextOptions>();
    command->add_option("--device", options->device,
                        "Device index as listed here, or part of its name; digits are always an index "
                        "(default: best available)")
        ->check(nonEmpty("an index or part of a name"));
    return [command, options]() {
        if (!command->parsed()) {
            return -1;
        }
        VulkanContext context(*options);
        std::printf("Vulkan devices:\n");
        for (const DeviceDescription& d : context.allDevices()) {
            bool chosen = d.index == context.description().index;
            std::printf("  %s[%u] %s (%s, Vulkan %s, driver %s)\n", chosen ? "* " : "  ", d.index, d.name.c_str(),
                        d.type.c_str(), d.apiVersion.c_str(), d.driver.c_str());
            for (const std::string& missing : d.missingFeatures) {
                std::printf("        missing: %s\n", missing.c_str());
            }
        }
        std::printf("Chosen: [%u] %s\n", context.description().index, context.description().name.c_str());
        std::printf("Features used:\n");
        for (const std::string& f : VulkanContext::requiredFeatures()) {
            std::printf("  %s\n", f.c_str());
        }
        requireNoValidationMessages(context);
        return 0;
    };
}

}  // namespace vkdr
