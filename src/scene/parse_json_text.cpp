#include "scene/parse_json_text.h"

#include <algorithm>
#include <set>
#include <vector>

#include "scene/gltf_diagnostics.h"

namespace vkdr {
namespace {

// An object or array being read: its path, and the keys it has given (an object) or
// how many entries it has (an array).
struct OpenContainer {
    std::string field;
    bool isArray = false;
    size_t entries = 0;
    std::set<std::string> keys;
    std::string pendingKey;  // of the member whose value comes next
};

// A reading of the text's events that keeps no values: nlohmann's parser with a
// callback rescans a container after each object in it, quadratic in the entries of a
// glTF's arrays, so the shape is read in a pass of its own.
template <typename Json>
class ShapeReader : public nlohmann::json_sax<Json> {
public:
    using Sax = nlohmann::json_sax<Json>;

    int depth() const { return depth_; }
    const std::optional<std::string>& repeatedKey() const { return repeatedKey_; }

    bool null() override { return primitive(); }
    bool boolean(bool) override { return primitive(); }
    bool number_integer(typename Sax::number_integer_t) override { return primitive(); }
    bool number_unsigned(typename Sax::number_unsigned_t) override { return primitive(); }
    bool number_float(typename Sax::number_float_t, const typename Sax::string_t&) override { return primitive(); }
    bool string(typename Sax::string_t&) override { return primitive(); }
    bool binary(typename Sax::binary_t&) override { return primitive(); }
    bool start_object(std::size_t) override { return start(false); }
    bool start_array(std::size_t) override { return start(true); }
    bool end_object() override { return end(); }
    bool end_array() override { return end(); }
    bool key(typename Sax::string_t& key) override {
        OpenContainer& object = open_.back();
        object.pendingKey = key;
        if (!object.keys.insert(key).second && !repeatedKey_) repeatedKey_ = fieldOf(object, key);
        noteDepth();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;  // the document parse that follows reports it
    }

private:
    // The root's members are named by their key alone.
    std::string fieldOf(const OpenContainer& object, const std::string& key) const {
        return open_.size() == 1 ? key : member(object.field, key);
    }
    void noteDepth() { depth_ = std::max(depth_, int(open_.size())); }
    // A primitive needs only its place in an array: no key can repeat under it.
    bool primitive() {
        noteDepth();
        if (!open_.empty() && open_.back().isArray) ++open_.back().entries;
        return true;
    }
    bool start(bool isArray) {
        std::string field;
        if (!open_.empty()) {
            OpenContainer& parent = open_.back();
            field = parent.isArray ? indexed(parent.field, parent.entries++) : fieldOf(parent, parent.pendingKey);
        }
        noteDepth();
        open_.push_back({std::move(field), isArray, 0, {}, ""});
        return true;
    }
    bool end() {
        open_.pop_back();
        return true;
    }

    std::vector<OpenContainer> open_;
    int depth_ = 0;
    std::optional<std::string> repeatedKey_;
};

}  // namespace

template <typename Json>
ParsedJsonText<Json> parseJsonText(std::string_view text, bool allowExceptions) {
    ShapeReader<Json> shape;
    Json::sax_parse(text, &shape);
    return {Json::parse(text, nullptr, allowExceptions), shape.repeatedKey(), shape.depth()};
}

template ParsedJsonText<nlohmann::json> parseJsonText(std::string_view, bool);
template ParsedJsonText<nlohmann::ordered_json> parseJsonText(std::string_view, bool);

}  // namespace vkdr
