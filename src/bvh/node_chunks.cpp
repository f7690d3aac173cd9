#include "bvh/node_chunks.h"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace vkdr::bvh_build {
namespace {

// Where one chunk's nodes go in the flattened array.
struct Placement {
    const NodeChunk* chunk;
    uint32_t root;      // the index of chunk->nodes[0]
    uint32_t restBase;  // the index of chunk->nodes[1]
    // For the chunk's grafts placed so far: each one's insertAt, and the nodes that
    // it and the grafts before it add before that point (their roots fill slots).
    std::vector<uint32_t> insertAt, added;

    uint32_t indexOf(uint32_t local) const {
        if (local == 0) return root;
        size_t before = size_t(std::upper_bound(insertAt.begin(), insertAt.end(), local) - insertAt.begin());
        return restBase + (local - 1) + (before > 0 ? added[before - 1] : 0);
    }
};

// Places chunk and, depth first, its grafts; returns how many nodes they hold together.
uint32_t place(const NodeChunk& chunk, uint32_t root, uint32_t restBase, std::vector<Placement>& placements) {
    const size_t index = placements.size();
    placements.push_back({&chunk, root, restBase, {}, {}});
    uint32_t added = 0;
    for (const NodeChunk::Graft& graft : chunk.grafts) {
        // Grafts later in the list lie after this one's slot: they do not move it.
        uint32_t graftRoot = placements[index].indexOf(graft.slot);
        uint32_t graftRest = restBase + (graft.insertAt - 1) + added;
        added += place(*graft.chunk, graftRoot, graftRest, placements) - 1;
        placements[index].insertAt.push_back(graft.insertAt);
        placements[index].added.push_back(added);
    }
    return uint32_t(chunk.nodes.size()) + added;
}

BvhNode relinked(BvhNode node, const Placement& placement) {
    if (node.count == 0) node.firstOrChild = placement.indexOf(node.firstOrChild);
    return node;
}

}  // namespace

std::vector<BvhNode> flattenNodeChunks(const NodeChunk& root) {
    std::vector<Placement> placements;
    std::vector<BvhNode> nodes(place(root, 0, 1, placements));
    // Every index receives one chunk's node, except the slots held for grafts' roots:
    // their placeholders are copied here and overwritten below.
    tbb::parallel_for(size_t(0), placements.size(), [&](size_t i) {
        const Placement& placement = placements[i];
        const std::vector<BvhNode>& chunkNodes = placement.chunk->nodes;
        for (uint32_t local = 1; local < chunkNodes.size(); ++local)
            nodes[placement.indexOf(local)] = relinked(chunkNodes[local], placement);
    });
    for (const Placement& placement : placements) nodes[placement.root] = relinked(placement.chunk->nodes[0], placement);
    return nodes;
}

}  // namespace vkdr::bvh_build
