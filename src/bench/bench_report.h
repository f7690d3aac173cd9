#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/scene_benchmark.h"

namespace vkdr {

struct SkippedScene {
    std::string name;
    std::string reason;
};

struct BenchReport {
    std::string device;
    std::string driver;
    uint32_t iterations = 0;
    std::vector<SceneBenchmark> scenes;
    std::vector<SkippedScene> skipped;
};

// One row per scene, for people; times in milliseconds.
std::string markdownTable(const BenchReport& report);

// {"device", "driver", "iterations", "scenes": [...], "skipped": [...]}; each scene
// has the fields docs/performance.md lists.
nlohmann::ordered_json reportJson(const BenchReport& report);

}  // namespace vkdr
