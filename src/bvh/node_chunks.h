#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "bvh/bvh.h"

namespace vkdr::bvh_build {

// The nodes one build task appends, with child links indexing its own vector. A
// subtree that another task builds at the same time goes into a chunk of its own,
// grafted in when both are done: its root fills a slot reserved among this chunk's
// nodes, and the rest of its nodes belong after the ones this chunk had by then.
// Grafting records where chunks go; flattenNodeChunks moves every node once, in
// parallel, instead of each task copying its subtree into its parent's vector.
struct NodeChunk {
    struct Graft {
        uint32_t slot;      // index in nodes of the placeholder for the graft's root
        uint32_t insertAt;  // the graft's other nodes come before nodes[insertAt]
        std::unique_ptr<NodeChunk> chunk;
    };
    std::vector<BvhNode> nodes;
    std::vector<Graft> grafts;  // in the order they were grafted; insertAt never decreases

    void graft(uint32_t slot, std::unique_ptr<NodeChunk> chunk) {
        grafts.push_back({slot, uint32_t(nodes.size()), std::move(chunk)});
    }
};

// All of the chunks' nodes in one array, in the order a single task appending every
// node to one vector would have given: a graft's nodes follow the ones its chunk had
// when it was grafted.
std::vector<BvhNode> flattenNodeChunks(const NodeChunk& root);

}  // namespace vkdr::bvh_build
