#pragma once
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkdr {

// Standard base64 (RFC 4648, with padding): how a page embeds a PNG as a data: URI, and
// how a checkpoint stores its long vectors of doubles.
std::string base64(std::span<const unsigned char> bytes);

// The bytes base64() encoded as `text`; nothing for text it would not have written: a
// length not a multiple of 4, a character outside the alphabet, padding other than at
// the end, or bits set under the padding.
std::optional<std::vector<unsigned char>> decodeBase64(std::string_view text);

}  // namespace vkdr
