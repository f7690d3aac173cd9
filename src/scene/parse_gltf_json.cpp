#include "scene/parse_gltf_json.h"

#include <string>
#include <utility>

#include "scene/parse_json_text.h"

namespace vkdr {
namespace {

// A scene's own structure nests a few levels, the data in "extras" a few more.
constexpr int kMaxJsonDepth = 512;

}  // namespace

nlohmann::json parseGltfJson(std::string_view text, const GltfDiagnostics& diagnostics) {
    ParsedJsonText<nlohmann::json> parsed = parseJsonText<nlohmann::json>(text, false);
    if (parsed.depth > kMaxJsonDepth) {
        diagnostics.fail("", "its JSON nests values " + std::to_string(parsed.depth) + " levels deep; at most " +
                                 std::to_string(kMaxJsonDepth) + " are read");
    }
    if (parsed.repeatedKey && parsed.document.is_object()) {
        diagnostics.fail(*parsed.repeatedKey, kRepeatedKeyProblem);
    }
    return std::move(parsed.document);
}

}  // namespace vkdr
