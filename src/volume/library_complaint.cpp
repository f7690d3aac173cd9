#include "volume/library_complaint.h"

#include <cctype>

namespace vkdr {

std::string boundedComplaint(std::string_view text) {
    constexpr size_t kMostCharacters = 200;
    std::string bounded;
    for (char c : text) {
        const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
        if (space && (bounded.empty() || bounded.back() == ' ')) continue;
        if (bounded.size() == kMostCharacters) return bounded + "...";
        bounded += space ? ' ' : c;
    }
    while (!bounded.empty() && bounded.back() == ' ') bounded.pop_back();
    return bounded;
}

}  // namespace vkdr
