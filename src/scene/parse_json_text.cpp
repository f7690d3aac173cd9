#include "scene/parse_json_text.h"

#include <algorithm>
#include <set>
#include <vector>

#include "scene/gltf_diagnostics.h"

namespace vkdr {
namespace {

// An object or array being read: where it is in its parent, and the keys it has given
// (an object) or how many entries it has (an array). Its path is built from these only
// for a message: held whole at every level, the paths of text nested n deep take memory
// in n^2 (15 GB for a 200 KB file nested 100,000 deep).
struct OpenContainer {
    bool isArray = false;
    std::string keyInParent;  // where the parent is an object
    size_t indexInParent = 0;  // where the parent is an array
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
        if (!object.keys.insert(key).second && !repeatedKey_) repeatedKey_ = fieldOf(open_.size() - 1, key);
        noteDepth();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;  // the document parse that follows reports it
    }

private:
    // The path of the container at `level` of open_ (the root's is empty); its members
    // are named by the key after it, the root's by their key alone.
    std::string pathOf(size_t level) const {
        std::string path;
        for (size_t i = 1; i <= level; ++i) {
            const OpenContainer& child = open_[i];
            path = open_[i - 1].isArray ? indexed(path, child.indexInParent) : fieldOf(i - 1, path, child.keyInParent);
        }
        return path;
    }
    std::string fieldOf(size_t level, const std::string& path, const std::string& key) const {
        return level == 0 ? key : member(path, key);
    }
    std::string fieldOf(size_t level, const std::string& key) const { return fieldOf(level, pathOf(level), key); }
    void noteDepth() { depth_ = std::max(depth_, int(open_.size())); }
    // A primitive needs only its place in an array: no key can repeat under it.
    bool primitive() {
        noteDepth();
        if (!open_.empty() && open_.back().isArray) ++open_.back().entries;
        return true;
    }
    bool start(bool isArray) {
        OpenContainer container{.isArray = isArray};
        if (!open_.empty()) {
            OpenContainer& parent = open_.back();
            if (parent.isArray) {
                container.indexInParent = parent.entries++;
            } else {
                container.keyInParent = parent.pendingKey;
            }
        }
        noteDepth();
        open_.push_back(std::move(container));
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
