#pragma once
#include <filesystem>
#include <span>
#include <string>

namespace vkdr {

// An optimisation's output directory belongs to one run: a new run never writes over
// another run's files, whose log and checkpoint it would mix with its own.

// The files a run writes (optimize/optimization_run.h); a directory holding any of them
// holds a run.
std::span<const char* const> runFileNames();

// The files an experiment writes besides (optimize/experiment_run.h).
std::span<const char* const> experimentFileNames();

enum class RunStart {
    New,        // into a directory that holds no run (or does not exist yet)
    Overwrite,  // replacing the run the directory holds, if any
    Resume,     // continuing the run the directory holds, from its checkpoint
};

// Throws vkdr::Error unless `directory` can take a run started as `start`: New refuses a
// directory that holds a run (saying how to overwrite or resume it), Overwrite one where
// a run file's name is taken by a directory, Resume one without a checkpoint.
void requireRunDirectoryFor(const std::filesystem::path& directory, RunStart start);

// Removes from `directory` every run file, and the experiment files too when asked,
// leaving all other files alone: what --overwrite does before the new run writes.
void removeRunFiles(const std::filesystem::path& directory, bool experimentFiles);

}  // namespace vkdr
