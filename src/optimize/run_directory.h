#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vkdr {

// An optimisation's output directory belongs to one run: a new run never writes over
// another run's files, whose log and checkpoint it would mix with its own.

// Whether a run writes a file of this name into its directory (optimize/optimization_run.h:
// log.jsonl, checkpoint.json, params.json, scene.gltf with what it refers to beside it
// (textures, density grids),
// final.exr, final.png, diff.png, loss.svg, report.html), or, for an experiment, besides
// (optimize/experiment_run.h: target.exr, target.png). A directory holding any of them
// holds a run.
bool isRunFileName(const std::string& name, bool experiment);

// The run files (isRunFileName) in `directory`, sorted; none when it does not exist.
std::vector<std::string> presentRunFiles(const std::filesystem::path& directory, bool experiment);

enum class RunStart {
    New,        // into a directory that holds no run (or does not exist yet)
    Overwrite,  // replacing the run the directory holds, if any
    Resume,     // continuing the run the directory holds, from its checkpoint
};

// Throws vkdr::Error unless `directory` can take a run started as `start`: New refuses a
// directory that holds a run (saying how to overwrite or resume it), Overwrite one where
// a run file's name is taken by a directory, Resume one without a checkpoint.
void requireRunDirectoryFor(const std::filesystem::path& directory, RunStart start, bool experiment = false);

// Removes from `directory` every run file (isRunFileName), leaving all other files
// alone: what --overwrite does before the new run writes.
void removeRunFiles(const std::filesystem::path& directory, bool experiment);

// Removes the run files but the log and the checkpoint: the outputs of a finished run
// that a resumed run writes again at its end. Removed before it rewrites the log, they
// cannot outlive it stopped short of its end, describing a run its log no longer holds.
void removeRunOutputs(const std::filesystem::path& directory, bool experiment);

}  // namespace vkdr
