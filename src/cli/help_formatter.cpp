#include "cli/help_formatter.h"

namespace vkdr {
namespace {

// CLI11 names an option's type, then its validators' descriptions after a colon:
// "UINT:an integer from 1 to 16384".
std::string typeOf(const CLI::Option* option) {
    const std::string name = option->get_type_name();
    return name.substr(0, name.find(':'));
}

std::string acceptedValues(const CLI::Option* option) {
    const std::string name = option->get_type_name();
    const size_t colon = name.find(':');
    return colon == std::string::npos ? "" : name.substr(colon + 1);
}

}  // namespace

std::string HelpFormatter::make_option_opts(const CLI::Option* option) const {
    if (option->get_type_name().empty()) {
        return "";  // a flag
    }
    const std::string type = typeOf(option);
    std::string text = type == "UINT" || type == "INT" ? " N" : type == "FLOAT" ? " X" : " TEXT";
    if (option->get_expected_max() == CLI::detail::expected_max_vector_size) {
        text += " ...";
    }
    if (option->get_required()) {
        text += " (required)";
    }
    return text;
}

std::string HelpFormatter::make_option_desc(const CLI::Option* option) const {
    std::string details = acceptedValues(option);
    if (!option->get_default_str().empty()) {
        details += (details.empty() ? "" : "; ") + std::string("default ") + option->get_default_str();
    }
    return details.empty() ? option->get_description() : option->get_description() + " (" + details + ")";
}

}  // namespace vkdr
