#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vkdr {

// The chunks of a binary glTF file (glTF 2.0, "Binary glTF Layout"), as tinygltf reads
// them: the JSON chunk first, then an optional BIN chunk, the data of buffers[0].
struct GlbLayout {
    std::string problem;                     // why it cannot be read; "" when it can
    std::string_view json;
    std::optional<std::string_view> binary;
    std::vector<std::string> ignored;        // further chunks and trailing bytes, which tinygltf skips
};

// Views into `bytes`, which must outlive the result.
GlbLayout glbLayout(std::string_view bytes);

}  // namespace vkdr
