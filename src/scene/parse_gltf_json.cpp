#include "scene/parse_gltf_json.h"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace vkdr {
namespace {

// A scene's own structure nests a few levels, the data in "extras" a few more.
constexpr int kMaxJsonDepth = 512;

// An object or array being parsed: its JSON path, the keys it has given (an object) or
// how many entries it has (an array).
struct OpenContainer {
    std::string field;
    bool isArray = false;
    size_t entries = 0;
    std::set<std::string> keys;
    std::string pendingKey;  // of the member whose value comes next
};

}  // namespace

nlohmann::json parseGltfJson(std::string_view text, const GltfDiagnostics& diagnostics) {
    using Json = nlohmann::json;
    int deepest = 0;
    std::string repeatedKey;
    std::vector<OpenContainer> open;
    // The path of the value that starts now, counted as an entry of its container.
    auto nextValueField = [&]() -> std::string {
        if (open.empty()) return "";
        OpenContainer& parent = open.back();
        if (parent.isArray) return indexed(parent.field, parent.entries++);
        return parent.field.empty() ? parent.pendingKey : member(parent.field, parent.pendingKey);
    };
    auto noteShape = [&](int depth, Json::parse_event_t event, Json& parsed) {
        deepest = std::max(deepest, depth);
        switch (event) {
        case Json::parse_event_t::object_start:
        case Json::parse_event_t::array_start:
            open.push_back({nextValueField(), event == Json::parse_event_t::array_start, 0, {}, ""});
            break;
        case Json::parse_event_t::object_end:
        case Json::parse_event_t::array_end:
            open.pop_back();
            break;
        case Json::parse_event_t::key: {
            OpenContainer& object = open.back();
            object.pendingKey = parsed.get<std::string>();
            if (!object.keys.insert(object.pendingKey).second && repeatedKey.empty()) {
                repeatedKey = object.field.empty() ? object.pendingKey : member(object.field, object.pendingKey);
            }
            break;
        }
        case Json::parse_event_t::value:
            nextValueField();
            break;
        }
        return true;
    };
    Json document = Json::parse(text, noteShape, false);
    if (deepest > kMaxJsonDepth) {
        diagnostics.fail("", "its JSON nests values " + std::to_string(deepest) + " levels deep; at most " +
                                 std::to_string(kMaxJsonDepth) + " are read");
    }
    if (!repeatedKey.empty() && document.is_object()) {
        diagnostics.fail(repeatedKey, "given twice in one object; glTF requires each key once");
    }
    return document;
}

}  // namespace vkdr
