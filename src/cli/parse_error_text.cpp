#include "cli/parse_error_text.h"

#include <regex>
#include <vector>

namespace vkdr {
namespace {

// CLI11's reason, except for an option of one value given more than once, which CLI11
// reports as "--spp: At Most 1 required but received 2".
std::string reasonOf(const CLI::ParseError& error) {
    static const std::regex kRepeated("(.+): At Most 1 required but received ([0-9]+)");
    std::cmatch repeated;
    if (std::regex_match(error.what(), repeated, kRepeated)) {
        return repeated[1].str() + ": given " + repeated[2].str() + " times; give it once";
    }
    return error.what();
}

}  // namespace

std::string parseErrorText(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
    const std::string program = app.get_name();
    std::vector<CLI::App*> given = app.get_subcommands();
    if (!given.empty()) {
        return reasonOf(error) + "; see '" + program + " " + given.front()->get_name() + " --help'";
    }
    std::string commands;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
        commands += (commands.empty() ? "" : ", ") + command->get_name();
    }
    if (argc > 1 && argv[1][0] != '-') {
        return "unknown command '" + std::string(argv[1]) + "'; the commands are " + commands + " (see '" + program +
               " --help')";
    }
    return reasonOf(error) + ": one of " + commands + " (see '" + program + " --help')";
}

}  // namespace vkdr
