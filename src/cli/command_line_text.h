#pragma once
#include <string>

namespace vkdr {

// The command line as a shell would take it back: arguments with characters outside
// [A-Za-z0-9_./=:,+-] in single quotes. For records of a run (report.html).
std::string commandLineText(int argc, const char* const* argv);

}  // namespace vkdr
