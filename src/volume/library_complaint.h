#pragma once
#include <string>
#include <string_view>

namespace vkdr {

// A library's complaint about a damaged file, fit for one line of a message: such a
// complaint can quote what the library read there (a "name" of gigabytes of spaces, say).
// Runs of white space become one space, and the text is cut after 200 characters.
std::string boundedComplaint(std::string_view text);

}  // namespace vkdr
