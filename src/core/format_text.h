#pragma once
#include <cstdio>
#include <string>

namespace vkdr {

// printf into a string, for tables, reports and SVG elements; text beyond 511
// characters is cut.
template <typename... Values>
std::string formatText(const char* pattern, Values... values) {
    char text[512];
    std::snprintf(text, sizeof(text), pattern, values...);
    return text;
}

}  // namespace vkdr
