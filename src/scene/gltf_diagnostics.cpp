#include "scene/gltf_diagnostics.h"

#include <algorithm>
#include <charconv>

#include "core/error.h"
#include "core/printable_text.h"

namespace vkdr {

std::string GltfDiagnostics::message(std::string_view field, std::string_view text) const {
    std::string result = fileName_ + ": ";
    if (!field.empty()) {
        result.append(field).append(": ");
    }
    return result.append(text);
}

void GltfDiagnostics::fail(std::string_view field, std::string_view text) const {
    throw Error(message(field, text));
}

void GltfDiagnostics::warn(std::string_view field, std::string_view text) {
    // A name from the file may hold control characters, as an error's does (core/error.h).
    std::string warning = printableText(message(field, text));
    if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end()) {
        warnings_.push_back(std::move(warning));
    }
}

std::string indexed(std::string_view array, size_t index) {
    return std::string(array) + "[" + std::to_string(index) + "]";
}

std::string member(std::string_view object, std::string_view key) {
    return std::string(object) + "." + std::string(key);
}

std::string formatNumber(double value) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, ec == std::errc() ? end : text);
}

}  // namespace vkdr
