#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace vkdr {

// The command line's help in words: an option's value shows as N (an integer), X (a
// number) or TEXT, and what it accepts and its default join its description, where
// CLI11 would print its type and validator names ("--spp UINT:UINT in [1 - 1048576]=16"
// becomes "--spp N   Samples per pixel (an integer from 1 to 1048576; default 16)").
class HelpFormatter : public CLI::Formatter {
public:
    std::string make_option_opts(const CLI::Option* option) const override;
    std::string make_option_desc(const CLI::Option* option) const override;
};

}  // namespace vkdr
