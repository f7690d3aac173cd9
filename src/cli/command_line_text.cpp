#include "cli/command_line_text.h"

#include <cstring>

namespace vkdr {
namespace {

std::string shellQuoted(const std::string& argument) {
    constexpr const char* kPlain =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./=:,+-";
    if (!argument.empty() && argument.find_first_not_of(kPlain) == std::string::npos) return argument;
    std::string quoted = "'";
    for (char c : argument) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

}  // namespace

std::string commandLineText(int argc, const char* const* argv) {
    std::string text;
    for (int i = 0; i < argc; ++i) text += (i == 0 ? "" : " ") + shellQuoted(argv[i]);
    return text;
}

}  // namespace vkdr
