#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace vkdr {

// Each subcommand registers its options on the app and returns the action to run
// once the command line has parsed; the action returns the process exit code.
using CommandAction = std::function<int()>;

CommandAction addRenderCommand(CLI::App& app);
CommandAction addInfoCommand(CLI::App& app);
CommandAction addGradCommand(CLI::App& app);
// commandLine: the whole command as typed, recorded in the run's report.html.
CommandAction addOptimizeCommand(CLI::App& app, std::string commandLine);
CommandAction addBenchCommand(CLI::App& app);
// `help [COMMAND]`: the same text as COMMAND --help.
CommandAction addHelpCommand(CLI::App& app);

}  // namespace vkdr
