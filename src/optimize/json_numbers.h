#pragma once
#include <charconv>
#include <cstdlib>
#include <span>

#include <nlohmann/json.hpp>

#include "optimize/value_summary.h"

namespace vkdr {

// The shortest decimal that reads back as `value`: parameters are floats, and 0.05f
// reads better in a log as 0.05 than as 0.05000000074505806.
inline double shortestDecimal(float value) {
    char text[32];
    auto [end, ec] = std::to_chars(text, text + sizeof(text) - 1, value);
    *end = '\0';
    return std::strtod(text, nullptr);
}

// A parameter of many values as optimize's outputs give it (optimize/value_summary.h).
inline nlohmann::ordered_json summaryJson(const ValueSummary& summary) {
    return {{"count", summary.count}, {"mean", summary.mean}, {"min", summary.minimum}, {"max", summary.maximum}};
}

inline nlohmann::ordered_json floatArray(std::span<const float> values) {
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (float value : values) array.push_back(shortestDecimal(value));
    return array;
}

}  // namespace vkdr
