#include "optimize/json_without_repeated_keys.h"

#include <set>
#include <vector>

namespace vkdr {

JsonWithRepeatedKey parseJsonNotingRepeatedKeys(std::string_view text) {
    using Json = nlohmann::ordered_json;
    std::vector<std::set<std::string>> openObjects;
    std::string repeated;
    auto noteKeys = [&](int, Json::parse_event_t event, Json& parsed) {
        if (event == Json::parse_event_t::object_start) openObjects.emplace_back();
        if (event == Json::parse_event_t::object_end) openObjects.pop_back();
        if (event == Json::parse_event_t::key && !openObjects.back().insert(parsed.get<std::string>()).second &&
            repeated.empty()) {
            repeated = parsed.get<std::string>();
        }
        return true;
    };
    Json document = Json::parse(text, noteKeys);
    return {std::move(document), std::move(repeated)};
}

}  // namespace vkdr
