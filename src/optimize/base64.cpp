#include "optimize/base64.h"

#include <algorithm>
#include <cstdint>

namespace vkdr {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// The 6-bit value of a digit; -1 for any other character.
int digitValue(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

}  // namespace

std::string base64(std::span<const unsigned char> bytes) {
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

std::optional<std::vector<unsigned char>> decodeBase64(std::string_view text) {
    if (text.size() % 4 != 0) return std::nullopt;
    std::vector<unsigned char> bytes;
    bytes.reserve(text.size() / 4 * 3);
    for (size_t i = 0; i < text.size(); i += 4) {
        const bool last = i + 4 == text.size();
        // Only the last group may end in padding: "xx==" holds one byte, "xxx=" two.
        const size_t padding = last ? (text[i + 3] == '=' ? (text[i + 2] == '=' ? 2 : 1) : 0) : 0;
        uint32_t group = 0;
        for (size_t digit = 0; digit < 4; ++digit) {
            const int value = digit < 4 - padding ? digitValue(text[i + digit]) : 0;
            if (value < 0) return std::nullopt;
            group = group << 6 | uint32_t(value);
        }
        const size_t count = 3 - padding;
        if ((group & ((1u << (8 * padding)) - 1u)) != 0) return std::nullopt;
        for (size_t k = 0; k < count; ++k) {
            bytes.push_back(static_cast<unsigned char>(group >> (16 - 8 * k)));
        }
    }
    return bytes;
}

}  // namespace vkdr
