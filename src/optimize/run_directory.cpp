#include "optimize/run_directory.h"

#include <algorithm>
#include <array>
#include <regex>
#include <span>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "optimize/checkpoint.h"

namespace vkdr {
namespace fs = std::filesystem;
namespace {

constexpr std::array<const char*, 9> kRunFiles = {"log.jsonl", "checkpoint.json", "params.json",
                                                  "scene.gltf", "final.exr",      "final.png",
                                                  "diff.png",  "loss.svg",        "report.html"};
constexpr std::array<const char*, 2> kExperimentFiles = {"target.exr", "target.png"};
// What scene.gltf refers to beside it (scene/write_scene.h): a .glb's binary chunk,
// base colour textures, density, emission and albedo grids, and copies of external files
// from outside the directory.
const std::regex kSceneCompanion(
    R"(scene\.(bin|image[0-9]+\.png|(materials[0-9]+\.)?(density|emission_grid|albedo_grid)\.vdb|)"
    R"((buffers|images)[0-9]+(\.[A-Za-z0-9]+)?))");

bool present(const fs::path& file) {
    std::error_code error;
    return fs::exists(fs::symlink_status(file, error));
}

std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

}  // namespace

std::vector<std::string> presentRunFiles(const fs::path& directory, bool experiment) {
    std::vector<std::string> found;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
        std::string name = entry.path().filename().string();
        if (isRunFileName(name, experiment)) found.push_back(name);
    }
    std::sort(found.begin(), found.end());
    return found;
}

bool isRunFileName(const std::string& name, bool experiment) {
    auto named = [&](const auto& names) { return std::find(names.begin(), names.end(), name) != names.end(); };
    return named(kRunFiles) || std::regex_match(name, kSceneCompanion) || (experiment && named(kExperimentFiles));
}

void requireRunDirectoryFor(const fs::path& directory, RunStart start, bool experiment) {
    const std::string dir = directory.string();
    if (start == RunStart::Resume) {
        if (!present(directory / kCheckpointFileName)) {
            throw Error("--resume " + dir + ": there is no " + kCheckpointFileName +
                        " (a run writes one every --checkpoint-every iterations)");
        }
        return;
    }
    std::vector<std::string> found = presentRunFiles(directory, experiment);
    if (found.empty()) return;
    if (start == RunStart::New) {
        throw Error("--out " + dir + " holds another run (" + listed(found) + "): give --overwrite to replace it, " +
                    (present(directory / kCheckpointFileName) ? "--resume " + dir + " to continue it, " : "") +
                    "or another --out");
    }
    for (const std::string& name : found) {
        std::error_code error;
        if (fs::is_directory(fs::symlink_status(directory / name, error))) {
            throw Error("--out " + dir + ": " + name + " is a directory; --overwrite replaces only files");
        }
    }
}

namespace {

void removeRunFilesBut(const fs::path& directory, bool experiment, std::span<const std::string_view> kept,
                       const std::string& why) {
    for (const std::string& name : presentRunFiles(directory, experiment)) {
        if (std::find(kept.begin(), kept.end(), name) != kept.end()) continue;
        std::error_code error;
        fs::remove(directory / name, error);
        if (error) throw Error(why + ": cannot remove " + (directory / name).string() + ": " + error.message());
    }
}

}  // namespace

void removeRunFiles(const fs::path& directory, bool experiment) {
    removeRunFilesBut(directory, experiment, {}, "--overwrite");
}

void removeRunOutputs(const fs::path& directory, bool experiment) {
    constexpr std::array<std::string_view, 2> kKept = {"log.jsonl", kCheckpointFileName};
    removeRunFilesBut(directory, experiment, kKept, "--resume");
}

}  // namespace vkdr
