#include "optimize/run_directory.h"

#include <array>
#include <vector>

#include "core/error.h"
#include "optimize/checkpoint.h"

namespace vkdr {
namespace fs = std::filesystem;
namespace {

constexpr std::array<const char*, 8> kRunFiles = {"log.jsonl", "checkpoint.json", "params.json", "scene.gltf",
                                                  "final.exr", "final.png",       "diff.png",    "loss.svg"};
constexpr std::array<const char*, 2> kExperimentFiles = {"target.exr", "target.png"};

bool present(const fs::path& file) {
    std::error_code error;
    return fs::exists(fs::symlink_status(file, error));
}

std::vector<std::string> presentRunFiles(const fs::path& directory) {
    std::vector<std::string> found;
    for (const char* name : kRunFiles) {
        if (present(directory / name)) found.push_back(name);
    }
    return found;
}

std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

}  // namespace

std::span<const char* const> runFileNames() {
    return kRunFiles;
}

std::span<const char* const> experimentFileNames() {
    return kExperimentFiles;
}

void requireRunDirectoryFor(const fs::path& directory, RunStart start) {
    const std::string dir = directory.string();
    if (start == RunStart::Resume) {
        if (!present(directory / kCheckpointFileName)) {
            throw Error("--resume " + dir + ": there is no " + kCheckpointFileName +
                        " (a run writes one every --checkpoint-every iterations)");
        }
        return;
    }
    std::vector<std::string> found = presentRunFiles(directory);
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

void removeRunFiles(const fs::path& directory, bool experimentFiles) {
    std::vector<std::string> names(kRunFiles.begin(), kRunFiles.end());
    if (experimentFiles) names.insert(names.end(), kExperimentFiles.begin(), kExperimentFiles.end());
    for (const std::string& name : names) {
        std::error_code error;
        fs::remove(directory / name, error);
        if (error) throw Error("--overwrite: cannot remove " + (directory / name).string() + ": " + error.message());
    }
}

}  // namespace vkdr
