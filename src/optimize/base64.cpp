#include "optimize/base64.h"

#include <algorithm>
#include <cstdint>

namespace vkdr {

std::string base64(std::span<const unsigned char> bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    text.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t count = std::min<size_t>(3, bytes.size() - i);
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (count > 1) group |= uint32_t(bytes[i + 1]) << 8;
        if (count > 2) group |= uint32_t(bytes[i + 2]);
        // Three bytes make four 6-bit digits; a short last group is padded with '='.
        for (size_t digit = 0; digit < 4; ++digit) {
            text += digit <= count ? kAlphabet[(group >> (18 - 6 * digit)) & 63] : '=';
        }
    }
    return text;
}

}  // namespace vkdr
