#pragma once
#include <filesystem>

#include "optimize/optimize_loop.h"
#include "optimize/run_identity.h"

namespace vkdr {

// The file an optimisation keeps its checkpoint in, in its output directory.
inline constexpr const char* kCheckpointFileName = "checkpoint.json";

struct Checkpoint {
    RunIdentity run;  // the run that wrote it
    LoopState state;
};

// Writes `checkpoint` atomically (image/atomic_write.h) as JSON, every number in full
// precision, so that reading it back gives the same doubles.
void writeCheckpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

// Reads what writeCheckpoint wrote. Throws vkdr::Error naming the file (and the key at
// fault) when it is missing, not a checkpoint, or damaged.
Checkpoint readCheckpoint(const std::filesystem::path& file);

}  // namespace vkdr
