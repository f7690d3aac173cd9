// The shape parseJsonText notes beside the document: repeated keys as paths, and depth.
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "scene/parse_json_text.h"

namespace vkdr::test {
namespace {

std::optional<std::string> repeatedKeyOf(const std::string& text) {
    return parseJsonText<nlohmann::ordered_json>(text).repeatedKey;
}

TEST(ParseJsonText, NamesARepeatedKeyByItsPathThroughObjectsAndArrays) {
    EXPECT_EQ(repeatedKeyOf(R"({"a": 1, "a": 2})"), "a");
    EXPECT_EQ(repeatedKeyOf(R"({"a": [{"x": 1}, {"x": 1, "x": 2}]})"), "a[1].x");
    EXPECT_EQ(repeatedKeyOf(R"({"a": [[1], [{"y": 0, "y": 1}]]})"), "a[1][0].y");
    EXPECT_EQ(repeatedKeyOf(R"({"a": {"b": [0, 1, {"c": {"d": 1, "d": {}}}]}})"), "a.b[2].c.d");
    EXPECT_EQ(repeatedKeyOf(R"([1, {"x": 1, "x": 2}])"), "[1].x");
    EXPECT_EQ(repeatedKeyOf(R"({"": 1, "": 2})"), "");  // an empty key is a key too
    EXPECT_EQ(repeatedKeyOf(R"({"a": {"x": 1}, "b": {"x": 1}, "c": [{"x": 1}, {"x": 2}]})"), std::nullopt);
}

TEST(ParseJsonText, KeepsTheParsersDocumentAndCountsDepth) {
    auto parsed = parseJsonText<nlohmann::ordered_json>(R"({"b": 1, "a": [[2]], "b": 3})");
    EXPECT_EQ(parsed.document.dump(), R"({"b":3,"a":[[2]]})");  // the parser's own choice: the last value
    EXPECT_EQ(parsed.depth, 3);  // the 2 lies in two arrays in the root object
    EXPECT_EQ(parseJsonText<nlohmann::json>("5").depth, 0);
}

TEST(ParseJsonText, TextThatIsNotJsonThrowsOrIsDiscarded) {
    for (const char* text : {R"({"a": 1, "a": 2)", "[1e999]", "", "{]"}) {
        SCOPED_TRACE(text);
        EXPECT_THROW(parseJsonText<nlohmann::json>(text), nlohmann::json::exception);
        EXPECT_TRUE(parseJsonText<nlohmann::json>(text, false).document.is_discarded());
    }
}

}  // namespace
}  // namespace vkdr::test
