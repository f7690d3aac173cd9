#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "optimize/optimize_loop.h"

namespace vkdr {

// The inputs that decide every iteration of an optimisation, by name ("scene",
// "parameters", "optimizer", ...), each as text. A checkpoint records the identity of
// the run that wrote it, and a run resumes from it only with the same identity.
using RunIdentity = std::map<std::string, std::string>;

// A target image as a command line names it: its camera ("" for the scene's first) and file.
struct TargetFile {
    std::string camera;
    std::filesystem::path file;
};

// What decides an optimisation's result besides its scene file, the loop's options and the loss.
struct RunInputs {
    std::filesystem::path experiment;      // the experiment file that set the run up; empty for a command line's
    std::vector<TargetFile> targets;       // a command line's targets
    std::vector<std::string> assignments;  // a command line's --set values, NAME=VALUE
    uint32_t spp = 0;
    uint32_t maxDepth = 0;
    bool equiangularSampling = true;       // RenderSettings::equiangularSampling
};

// The identity of a run: files by name and digest (an experiment's file stands for its
// targets and values), options as text. Throws vkdr::Error naming a file it cannot read.
RunIdentity runIdentity(const std::filesystem::path& sceneFile, const OptimizeOptions& options, LossKind loss,
                        const RunInputs& inputs);

// Adds to `identity` the files the scene reads besides its glTF (buffers, images,
// density grids) by name and digest, as "scene_files"; nothing for a scene that reads
// none. Throws vkdr::Error naming a file it cannot read.
void addSceneFiles(RunIdentity& identity, const Scene& scene);

// The file's size and a 64-bit FNV-1a hash of its bytes, as text: equal files give
// equal digests, and an edited file almost surely a different one. Throws vkdr::Error
// naming the file when it cannot be read.
std::string fileDigest(const std::filesystem::path& file);

// Throws vkdr::Error naming `checkpoint` and the first entry in which `current` differs
// from `written`, with both values. `written`'s --set values are compared as the floats
// they set, also where an older checkpoint holds them as typed.
void requireSameRun(const std::filesystem::path& checkpoint, const RunIdentity& written, const RunIdentity& current);

}  // namespace vkdr
