#pragma once
// Reads report.html back the way a test checks it: its embedded images, sections and
// table cells, by plain string search (the page is generated, not free-form HTML).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli_run.h"
#include "image/image.h"

namespace vkdr::test {

inline size_t occurrences(const std::string& text, const std::string& part) {
    size_t count = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

// The text between `open` (after its end) and the next `close`, for every `open`.
inline std::vector<std::string> between(const std::string& text, const std::string& open, const std::string& close) {
    std::vector<std::string> parts;
    for (size_t at = text.find(open); at != std::string::npos; at = text.find(open, at + 1)) {
        size_t start = at + open.size(), end = text.find(close, start);
        if (end == std::string::npos) break;
        parts.push_back(text.substr(start, end - start));
    }
    return parts;
}

// RFC 4648 base64 (written here, not taken from the code under test); nullopt on a
// character outside the alphabet or a length that is not a multiple of four.
inline std::optional<std::string> decodeBase64(const std::string& text) {
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (text.size() % 4 != 0) return std::nullopt;
    std::string bytes;
    for (size_t i = 0; i < text.size(); i += 4) {
        unsigned bits = 0;
        int padding = 0;
        for (size_t j = 0; j < 4; ++j) {
            char c = text[i + j];
            size_t value = alphabet.find(c);
            if (c == '=') {
                ++padding;
                value = 0;
            } else if (value == std::string::npos || padding > 0) {
                return std::nullopt;
            }
            bits = (bits << 6) | unsigned(value);
        }
        for (int k = 0; k < 3 - padding; ++k) bytes += char((bits >> (16 - 8 * k)) & 0xff);
    }
    return bytes;
}

// The image of the <img class="kind" ...> whose src is a base64 PNG, decoded through
// a file in `scratch` by the project's image reader; nullopt if there is none.
inline std::optional<Image> embeddedPng(const std::string& html, const std::string& kind,
                                        const std::filesystem::path& scratch) {
    size_t tag = html.find("<img class=\"" + kind + "\"");
    if (tag == std::string::npos) return std::nullopt;
    const std::string prefix = "src=\"data:image/png;base64,";
    size_t start = html.find(prefix, tag);
    if (start == std::string::npos || start > html.find('>', tag)) return std::nullopt;
    start += prefix.size();
    std::optional<std::string> png = decodeBase64(html.substr(start, html.find('"', start) - start));
    if (!png) return std::nullopt;
    std::filesystem::path file = scratch / (kind + ".png");
    std::ofstream(file, std::ios::binary) << *png;
    return readImage(file);
}

}  // namespace vkdr::test
