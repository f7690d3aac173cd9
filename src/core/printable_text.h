#pragma once
#include <cstdio>
#include <string>
#include <string_view>

namespace vkdr {

// `text` with every byte that is a control character or not part of valid UTF-8 written
// as \xNN: a message may quote a file's own bytes (a damaged channel name, a path), and
// must still print as one line on a terminal and convert to a Python str.
inline std::string printableText(std::string_view text) {
    auto escaped = [](unsigned char byte) {
        char code[5];
        std::snprintf(code, sizeof(code), "\\x%02x", byte);
        return std::string(code);
    };
    // The length of the UTF-8 sequence that starts at `i`, or 0 if none does.
    auto sequenceLength = [&](size_t i) -> size_t {
        const unsigned char lead = static_cast<unsigned char>(text[i]);
        const size_t length = lead >= 0xf0 && lead <= 0xf4 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 ? 2 : 0;
        if (length == 0 || lead > 0xf4 || i + length > text.size()) return 0;
        for (size_t k = 1; k < length; ++k) {
            if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) return 0;
        }
        // Overlong forms, UTF-16 surrogates and code points beyond U+10FFFF are not UTF-8.
        const unsigned char second = static_cast<unsigned char>(text[i + 1]);
        if ((lead == 0xe0 && second < 0xa0) || (lead == 0xed && second >= 0xa0) || (lead == 0xf0 && second < 0x90) ||
            (lead == 0xf4 && second >= 0x90)) {
            return 0;
        }
        return length;
    };
    std::string printable;
    for (size_t i = 0; i < text.size();) {
        const unsigned char byte = static_cast<unsigned char>(text[i]);
        if (byte >= 0x20 && byte < 0x7f) {
            printable += char(byte);
            ++i;
        } else if (const size_t length = byte >= 0x80 ? sequenceLength(i) : 0; length > 0) {
            printable.append(text.substr(i, length));
            i += length;
        } else {
            printable += escaped(byte);
            ++i;
        }
    }
    return printable;
}

}  // namespace vkdr
