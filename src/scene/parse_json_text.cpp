#include "scene/parse_json_text.h"

#include <algorithm>
#include <set>
#include <vector>

#include "scene/gltf_diagnostics.h"

namespace vkdr {
namespace {

// An object or array being parsed: its path, and the keys it has given (an object) or
// how many entries it has (an array).
struct OpenContainer {
    std::string field;
    bool isArray = false;
    size_t entries = 0;
    std::set<std::string> keys;
    std::string pendingKey;  // of the member whose value comes next
};

}  // namespace

template <typename Json>
ParsedJsonText<Json> parseJsonText(std::string_view text, bool allowExceptions) {
    ParsedJsonText<Json> parsed;
    std::vector<OpenContainer> open;
    // The path of the value that starts now, counted as an entry of its container.
    auto nextValueField = [&]() -> std::string {
        if (open.empty()) return "";
        OpenContainer& parent = open.back();
        if (parent.isArray) return indexed(parent.field, parent.entries++);
        return parent.field.empty() ? parent.pendingKey : member(parent.field, parent.pendingKey);
    };
    auto noteShape = [&](int depth, typename Json::parse_event_t event, Json& value) {
        parsed.depth = std::max(parsed.depth, depth);
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
            object.pendingKey = value.template get<std::string>();
            if (!object.keys.insert(object.pendingKey).second && parsed.repeatedKey.empty()) {
                parsed.repeatedKey =
                    object.field.empty() ? object.pendingKey : member(object.field, object.pendingKey);
            }
            break;
        }
        case Json::parse_event_t::value:
            nextValueField();
            break;
        }
        return true;
    };
    parsed.document = Json::parse(text, noteShape, allowExceptions);
    return parsed;
}

template ParsedJsonText<nlohmann::json> parseJsonText(std::string_view, bool);
template ParsedJsonText<nlohmann::ordered_json> parseJsonText(std::string_view, bool);

}  // namespace vkdr
