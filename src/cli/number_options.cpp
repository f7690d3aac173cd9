#include "cli/number_options.h"

#include "core/signed_decimal.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

namespace vkdr {
namespace {

// `text` whole as a decimal number (an optional sign, digits, a point, an exponent):
// not hexadecimal ("0x10", which CLI11 would read as 16), nor with spaces around it, as
// the integer options and --set read numbers.
std::optional<double> decimalNumber(const std::string& text) {
    const std::string_view number = withoutPlusSign(text);
    const char* end = number.data() + number.size();
    double value = 0.0;
    auto [stop, ec] = std::from_chars(number.data(), end, value, std::chars_format::general);
    if (ec != std::errc() || stop != end) return std::nullopt;
    return value;
}

CLI::Validator finiteNumberWhere(std::function<bool(double)> accepts, const std::string& wanted) {
    return CLI::Validator(
        [accepts, wanted](std::string& text) -> std::string {
            const std::optional<double> value = decimalNumber(text);
            if (value && std::isfinite(*value) && accepts(*value)) return "";
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

CLI::Validator integerIn(uint64_t low, uint64_t high, const std::string& kind) {
    const std::string expected =
        kind.empty() ? "an integer from " + std::to_string(low) + " to " + std::to_string(high) : kind;
    return CLI::Validator(
        [=](std::string& input) -> std::string {
            uint64_t value = 0;
            const char* end = input.data() + input.size();
            auto [stop, ec] = std::from_chars(input.data(), end, value);
            bool digitsOnly = !input.empty() && input.find_first_not_of("0123456789") == std::string::npos;
            if (!digitsOnly || ec != std::errc() || stop != end || value < low || value > high) {
                return "must be " + expected + ", got " + input;
            }
            input = std::to_string(value);
            return "";
        },
        expected);
}

CLI::Validator nonEmpty(const std::string& what) {
    return CLI::Validator([what](std::string& text) -> std::string { return text.empty() ? "give " + what : ""; },
                          "");
}

}  // namespace vkdr
