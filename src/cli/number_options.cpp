#include "cli/number_options.h"

#include <cmath>
#include <sstream>

namespace vkdr {
namespace {

CLI::Validator finiteNumberWhere(std::function<bool(double)> accepts, const std::string& wanted) {
    return CLI::Validator(
        [accepts, wanted](std::string& text) -> std::string {
            double value = 0.0;
            bool read = CLI::detail::lexical_cast(text, value);
            if (read && std::isfinite(value) && accepts(value)) return "";
            return "expected " + wanted + ", got " + text;
        },
        wanted);
}

std::string numberText(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

}  // namespace

CLI::Validator finitePositiveNumber() {
    return finiteNumberWhere([](double value) { return value > 0.0; }, "a finite number > 0");
}

CLI::Validator finiteNumberIn(double lower, double upper) {
    return finiteNumberWhere([lower, upper](double value) { return value >= lower && value <= upper; },
                             "a finite number in [" + numberText(lower) + ", " + numberText(upper) + "]");
}

}  // namespace vkdr
