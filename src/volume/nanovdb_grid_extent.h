#pragma once
// Whether a NanoVDB grid read from a file lies within the bytes read. NanoVDB's reader
// sizes its buffer by the file's metadata and then follows the grid's own sizes and
// offsets, and its validator checks neither the root's table against the buffer nor the
// leaf nodes, so a damaged file would be read past its end.
#include <cstdint>
#include <string>
#include <type_traits>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/NodeManager.h>

#include "core/error.h"

namespace vkdr {

// Throws vkdr::Error unless the `held` bytes at `bytes` hold a grid's and its tree's
// headers, and the whole of the size that header gives the grid.
void requireGridWithinBuffer(const uint8_t* bytes, uint64_t held);

// Throws vkdr::Error unless every node of `grid` (root table, internal nodes, leaves)
// lies within its gridSize() bytes, aligned, and the tree's header counts the nodes it
// holds: NanoVDB's validator and checksum address the nodes of each level by those
// counts (as an array from the level's first node where the grid is breadth-first and
// its leaves of one size, else through a table of as many entries, filled by walking
// the tree). Requires requireGridWithinBuffer first.
template <typename ValueT>
void requireNodesWithinGrid(const nanovdb::NanoGrid<ValueT>& grid) {
    const uintptr_t begin = reinterpret_cast<uintptr_t>(&grid);
    const uint64_t size = grid.gridSize();
    auto within = [&](const void* node, uint64_t bytes, const char* what) {
        const uintptr_t at = reinterpret_cast<uintptr_t>(node);
        if (at < begin || at - begin > size || size - (at - begin) < bytes || at % NANOVDB_DATA_ALIGNMENT != 0) {
            throw Error(std::string("the grid is damaged (") + what + " lies outside its " + std::to_string(size) +
                        " bytes)");
        }
    };
    const auto& tree = grid.tree();
    const auto& root = tree.root();
    within(&root, sizeof(root), "its root node");
    within(&root, root.memUsage(), "its root node's table");
    uint64_t held[3] = {0, 0, 0};  // leaves, lower and upper internal nodes
    for (auto upper = root.beginChild(); upper; ++upper) {
        within(&*upper, sizeof(*upper), "an upper internal node");
        ++held[2];
        for (auto lower = upper->beginChild(); lower; ++lower) {
            within(&*lower, sizeof(*lower), "a lower internal node");
            ++held[1];
            for (auto leaf = lower->beginChild(); leaf; ++leaf) {
                within(&*leaf, sizeof(*leaf), "a leaf node");
                ++held[0];
                // An FpN leaf's values follow it, as many bits each as its flags say.
                if constexpr (std::is_same_v<ValueT, nanovdb::FpN>) {
                    if (leaf->data()->bitWidth() > 16) {
                        throw Error("the grid is damaged (a leaf of its values takes " +
                                    std::to_string(leaf->data()->bitWidth()) + " bits each; at most 16 are defined)");
                    }
                    within(&*leaf, leaf->data()->memUsage(), "a leaf node's values");
                }
            }
        }
    }
    for (int level = 0; level < 3; ++level) {
        if (held[level] != tree.nodeCount(level)) {
            throw Error("the grid is damaged (its tree's header counts " + std::to_string(tree.nodeCount(level)) +
                        " nodes at level " + std::to_string(level) + ", its tree holds " + std::to_string(held[level]) +
                        ")");
        }
    }
    if (nanovdb::NodeManager<ValueT>::isLinear(grid)) {
        auto levelWithin = [&](const auto* first, uint64_t count, const char* what) {
            if (count > 0) within(first, count * sizeof(*first), what);
        };
        levelWithin(tree.template getFirstNode<0>(), held[0], "the array of its leaf nodes");
        levelWithin(tree.template getFirstNode<1>(), held[1], "the array of its lower internal nodes");
        levelWithin(tree.template getFirstNode<2>(), held[2], "the array of its upper internal nodes");
    }
}

}  // namespace vkdr
