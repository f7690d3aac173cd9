#pragma once
#include <cstdint>
#include <string>

namespace vkdr {

// Prints "warning: <text>" on stderr, as every subcommand tells the user of a problem it
// goes on despite.
void printWarning(const std::string& text);

// Warns that `paths` paths of `renders` were cut short (render/cut_paths.h); nothing
// when there were none.
void warnOfCutPaths(uint64_t paths, const std::string& renders);

}  // namespace vkdr
