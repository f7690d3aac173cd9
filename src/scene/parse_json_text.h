#pragma once
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vkdr {

// A JSON document with what nlohmann's parser keeps quiet about.
template <typename Json>
struct ParsedJsonText {
    Json document;
    // The first key the text gives twice in one object, as a path ("cameras[1].name"):
    // the parser keeps the last of two equal keys without a word, so in a file a person
    // edits, the value edited in one place and not the other would silently win or lose.
    std::optional<std::string> repeatedKey;
    // How many objects and arrays enclose the deepest value or key (the root's members
    // are at 1).
    int depth = 0;
};

// What a reader says of ParsedJsonText::repeatedKey.
inline constexpr const char* kRepeatedKeyProblem = "given twice in one object; give each key once";

// Parses `text` as nlohmann::json or nlohmann::ordered_json. Where it is not JSON, throws
// Json::exception (parse_error, or out_of_range for a number beyond double range), or
// with `allowExceptions` false gives a discarded document.
template <typename Json>
ParsedJsonText<Json> parseJsonText(std::string_view text, bool allowExceptions = true);

// A parse error's message for a person: nlohmann's without the error id it starts with
// ("[json.exception.parse_error.101] ").
inline std::string jsonErrorText(const nlohmann::json::exception& error) {
    const std::string message = error.what();
    const size_t idEnd = message.find("] ");
    return idEnd == std::string::npos ? message : message.substr(idEnd + 2);
}

extern template ParsedJsonText<nlohmann::json> parseJsonText(std::string_view, bool);
extern template ParsedJsonText<nlohmann::ordered_json> parseJsonText(std::string_view, bool);

}  // namespace vkdr
