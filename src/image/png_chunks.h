#pragma once
#include <cstddef>
#include <string>

namespace vkdr {

// For bytes that start with the PNG signature: what is wrong when a chunk declares more
// bytes than follow it (empty when every chunk fits, or the bytes are not a PNG).
// stb_image sizes its buffer for the compressed data by the declared lengths before
// reading them, so a few corrupt bytes could make it claim gigabytes; callers check this
// first.
std::string pngChunkProblem(const unsigned char* bytes, size_t size);

}  // namespace vkdr
