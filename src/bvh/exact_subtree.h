#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/build_records.h"
#include "bvh/bvh.h"

namespace vkdr::bvh_build {

// Ranges of at most this many triangles are built by buildExactSubtree. Most nodes
// of a tree are this small, and per node, setting up and sweeping bins cost more than
// the few triangles binned into them.
inline constexpr size_t kExactSubtreeSize = 64;

// Builds the subtree of range (at most kExactSubtreeSize triangles) with its root at
// nodes[nodeIndex], appending the rest of its nodes to nodes, and reorders
// boxes[range.begin, range.end) into leaf order. Every node takes the split of least
// SAH cost among all divisions of its triangles sorted by centroid along an axis: the
// exact object split, which no binned split beats.
void buildExactSubtree(std::span<TriangleBox> boxes, const BuildRange& range, uint32_t nodeIndex,
                       std::vector<BvhNode>& nodes);

}  // namespace vkdr::bvh_build
