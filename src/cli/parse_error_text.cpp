#include "cli/parse_error_text.h"

#include <vector>

namespace vkdr {

std::string parseErrorText(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
    const std::string program = app.get_name();
    std::vector<CLI::App*> given = app.get_subcommands();
    if (!given.empty()) {
        return std::string(error.what()) + "; see '" + program + " " + given.front()->get_name() + " --help'";
    }
    std::string commands;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
        commands += (commands.empty() ? "" : ", ") + command->get_name();
    }
    if (argc > 1 && argv[1][0] != '-') {
        return "unknown command '" + std::string(argv[1]) + "'; the commands are " + commands + " (see '" + program +
               " --help')";
    }
    return std::string(error.what()) + ": one of " + commands + " (see '" + program + " --help')";
}

}  // namespace vkdr
