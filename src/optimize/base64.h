#pragma once
#include <span>
#include <string>

namespace vkdr {

// Standard base64 (RFC 4648, with padding): how a page embeds a PNG as a data: URI.
std::string base64(std::span<const unsigned char> bytes);

}  // namespace vkdr
