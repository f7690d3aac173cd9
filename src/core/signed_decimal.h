#pragma once
#include <string_view>

namespace vkdr {

// `text` without a leading '+' sign, for std::from_chars, which reads a '-' but not a
// '+': "+0.5" is a number people write. A '+' before another sign stays, so "+-1" and
// "++1" are still refused.
inline std::string_view withoutPlusSign(std::string_view text) {
    if (text.size() > 1 && text[0] == '+' && text[1] != '+' && text[1] != '-') text.remove_prefix(1);
    return text;
}

}  // namespace vkdr
