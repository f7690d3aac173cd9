#include "optimize/json_without_repeated_keys.h"

#include <set>
#include <vector>

namespace vkdr {

JsonWithRepeatedKey parseJsonNotingRepeatedKeys(std::string_view text) {
    using Json = nlohmann::ordered_json;
    // Per open container: the key it is the value of ("" for the root and array
    // elements), and for an object the keys it has given.
    struct Open {
        std::string key;
        std::set<std::string> keys;
    };
    std::vector<Open> open;
    std::string pendingKey;
    std::string repeated;
    auto pathTo = [&](const std::string& key) {
        std::string path;
        for (const Open& container : open) {
            if (!container.key.empty()) path += container.key + ".";
        }
        return path + key;
    };
    auto noteKeys = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
        case Json::parse_event_t::object_start:
        case Json::parse_event_t::array_start:
            open.push_back({pendingKey, {}});
            pendingKey.clear();
            break;
        case Json::parse_event_t::object_end:
        case Json::parse_event_t::array_end:
            open.pop_back();
            break;
        case Json::parse_event_t::key: {
            const std::string key = parsed.get<std::string>();
            if (!open.back().keys.insert(key).second && repeated.empty()) repeated = pathTo(key);
            pendingKey = key;
            break;
        }
        case Json::parse_event_t::value:
            pendingKey.clear();
            break;
        }
        return true;
    };
    Json document = Json::parse(text, noteKeys);
    return {std::move(document), std::move(repeated)};
}

}  // namespace vkdr
