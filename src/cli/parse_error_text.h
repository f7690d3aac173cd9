#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace vkdr {

// The one line (without "error: ") for a command line CLI11 refuses: CLI11's reason, and
// where to read more ("see 'vkdiffrender render --help'"). A first word that names no
// command is said to be unknown, with the commands listed, where CLI11 would only say
// that a command is required.
std::string parseErrorText(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv);

}  // namespace vkdr
