#pragma once
#include <filesystem>
#include <string>

#include "optimize/optimize_loop.h"

namespace vkdr {

// One line of log.jsonl: {"iteration", "loss", "parameters": {name: [values]},
// "gradients": {name: [dLoss/dvalue]}, "forward_ms", "adjoint_ms"}, no newline.
std::string iterationJsonLine(const IterationRecord& record);

// log.jsonl, one line per iteration. The whole file is rewritten (atomically) after
// each iteration, so that a run stopped at any point leaves a complete, parseable log
// of the iterations done; a few hundred short lines cost nothing next to a render.
class IterationLog {
public:
    explicit IterationLog(std::filesystem::path file) : file_(std::move(file)) {}
    void append(const IterationRecord& record);

private:
    std::filesystem::path file_;
    std::string text_;
};

}  // namespace vkdr
