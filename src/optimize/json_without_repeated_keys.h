#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vkdr {

// A JSON document and the first key its text gives twice in one object (empty if none),
// after the keys of the objects it lies in: "start.media/fog/sigma_a".
// nlohmann's parser keeps the last of two equal keys without a word: in a file a person
// edits, the value edited in one place and not the other would silently win or lose.
struct JsonWithRepeatedKey {
    nlohmann::ordered_json document;
    std::string repeatedKey;
};

// What a reader says of JsonWithRepeatedKey::repeatedKey.
inline constexpr const char* kRepeatedKeyProblem = "given twice in one object; give each key once";

// Throws nlohmann::json::parse_error where `text` is not JSON.
JsonWithRepeatedKey parseJsonNotingRepeatedKeys(std::string_view text);

}  // namespace vkdr
