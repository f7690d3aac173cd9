#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"

namespace vkdr {

CommandAction addHelpCommand(CLI::App& app) {
    CLI::App* command = app.add_subcommand("help", "Print the help of a command (or of vkdiffrender)");
    auto name = std::make_shared<std::string>();
    command->add_option("command", *name, "render, grad, optimize, bench or info");
    return [&app, command, name]() {
        if (!command->parsed()) {
            return -1;
        }
        const CLI::App* subject = &app;
        if (!name->empty()) {
            std::string names;
            for (const CLI::App* sub : app.get_subcommands({})) {
                if (sub->get_name() == *name) subject = sub;
                names += (names.empty() ? "" : ", ") + sub->get_name();
            }
            if (subject == &app) {
                throw Error("help: no command '" + *name + "'; the commands are " + names);
            }
        }
        // Straight from the formatter: App::help() on the program would show the help of
        // the command parsed, `help` itself. The program's name leads a command's usage
        // line, as with --help.
        const std::string usage = subject == &app ? app.get_name() : app.get_name() + " " + subject->get_name();
        std::fputs(app.get_formatter()->make_help(subject, usage, CLI::AppFormatMode::Normal).c_str(), stdout);
        return 0;
    };
}

}  // namespace vkdr
