#include "bvh/exact_subtree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>

namespace vkdr::bvh_build {
namespace {

// Positions in a subtree fit in a byte.
static_assert(kExactSubtreeSize <= 256);
using Slot = uint8_t;

// Orders floats as their values do, -0 with +0, when compared as unsigned integers.
uint32_t orderedBits(float f) {
    uint32_t bits = std::bit_cast<uint32_t>(f + 0.0f);
    return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

struct ExactSplit {
    int axis = 0;
    uint32_t leftCount = 0;  // the first leftCount triangles in the axis's order go left
    float childCosts = std::numeric_limits<float>::infinity();  // summed count * half area
};

// The triangles of one subtree, sorted by centroid once along each axis. A node is a
// slice [begin, end) of all three orders holding the same triangles; splitting it
// partitions each order stably, so the children's slices stay sorted without sorting
// again.
class ExactSubtree {
public:
    explicit ExactSubtree(std::span<TriangleBox> boxes) : boxes_(boxes), count_(uint32_t(boxes.size())) {
        assert(boxes.size() <= kExactSubtreeSize);
        std::copy(boxes.begin(), boxes.end(), records_.begin());
        for (uint32_t i = 0; i < count_; ++i) {
            low_[i] = load4(boxes[i].min);
            high_[i] = load4(boxes[i].max);
            Float4 centroid = centroid4(low_[i], high_[i]);
            for (int axis = 0; axis < 3; ++axis) centroids_[axis][i] = centroid[axis];
        }
        // Equal centroids keep their order in the range, so the tree is deterministic.
        std::array<uint64_t, kExactSubtreeSize> keys;
        for (int axis = 0; axis < 3; ++axis) {
            for (uint32_t i = 0; i < count_; ++i) keys[i] = uint64_t(orderedBits(centroids_[axis][i])) << 32 | i;
            std::sort(keys.begin(), keys.begin() + count_);
            for (uint32_t i = 0; i < count_; ++i) order_[axis][i] = Slot(keys[i]);
        }
    }

    // Builds the node of slice [begin, end) at nodes[nodeIndex]; firstTriangle is
    // where the subtree's triangles start in the build's leaf order.
    void build(uint32_t begin, uint32_t end, uint32_t depth, const Bounds3& bounds, uint32_t nodeIndex,
               size_t firstTriangle, std::vector<BvhNode>& nodes) {
        const uint32_t count = end - begin;
        auto makeLeaf = [&] { nodes[nodeIndex] = {bounds.min, uint32_t(firstTriangle + begin), bounds.max, count}; };
        if (count == 1) return makeLeaf();

        ExactSplit split = findBestSplit(begin, end);
        // In a box without area (triangles along one axis-aligned line), every split
        // costs the same: the SAH cannot choose, and no ray is likely to enter the box.
        float nodeArea = bounds.halfArea();
        bool sahPrefersSplit = nodeArea > 0.0f && sahCost(split.childCosts, nodeArea) < float(count);
        if (!sahPrefersSplit && count <= kBvhMaxLeafTriangles) return makeLeaf();
        bool splitFits = fitsDepthLimit(depth + 1, split.leftCount) &&
                         fitsDepthLimit(depth + 1, count - split.leftCount);
        if (!sahPrefersSplit || !splitFits) split = medianSplit(begin, end);

        uint32_t middle = begin + split.leftCount;
        partition(split, begin, end);
        uint32_t firstChild = uint32_t(nodes.size());
        nodes.resize(nodes.size() + 2);
        nodes[nodeIndex] = {bounds.min, firstChild, bounds.max, 0};
        build(begin, middle, depth + 1, boundsOf(begin, middle), firstChild, firstTriangle, nodes);
        build(middle, end, depth + 1, boundsOf(middle, end), firstChild + 1, firstTriangle, nodes);
    }

    // Writes the records back in leaf order.
    void storeLeafOrder() const {
        for (uint32_t i = 0; i < count_; ++i) boxes_[i] = records_[order_[0][i]];
    }

private:
    // Sweeps the three axes' orders at once, one per SIMD lane (as the binned sweeps
    // do): from the right, keeping count * area to the right of every plane, then from
    // the left, pricing each plane. Ties go to the first axis, then the first plane.
    ExactSplit findBestSplit(uint32_t begin, uint32_t end) const {
        const uint32_t count = end - begin;
        auto extend = [&](std::array<Box4, 3>& boxes, uint32_t i) {
            for (int axis = 0; axis < 3; ++axis) {
                Slot slot = order_[axis][begin + i];
                boxes[axis].extend(low_[slot], high_[slot]);
            }
        };
        std::array<Float4, kExactSubtreeSize> rightCosts;  // rightCosts[i]: slots [begin + i, end), per axis
        std::array<Box4, 3> right;
        for (uint32_t i = count - 1; i >= 1; --i) {
            extend(right, i);
            rightCosts[i] = float(count - i) * halfAreas(right);
        }
        Float4 bestCost = Float4{} + std::numeric_limits<float>::infinity();
        Int4 bestCount{};
        std::array<Box4, 3> left;
        for (uint32_t i = 1; i < count; ++i) {
            extend(left, i - 1);
            Float4 cost = float(i) * halfAreas(left) + rightCosts[i];
            Int4 wins = cost < bestCost;
            bestCost = wins ? cost : bestCost;
            bestCount = wins ? Int4{} + int(i) : bestCount;
        }
        ExactSplit best;
        for (int axis = 0; axis < 3; ++axis)
            if (bestCost[axis] < best.childCosts) best = {axis, uint32_t(bestCount[axis]), bestCost[axis]};
        return best;
    }

    // Halves by count along the widest axis of the centroids; in the order of the
    // range where they coincide. Each order's ends hold its axis's extremes.
    ExactSplit medianSplit(uint32_t begin, uint32_t end) const {
        glm::vec3 extent;
        for (int axis = 0; axis < 3; ++axis)
            extent[axis] = centroids_[axis][order_[axis][end - 1]] - centroids_[axis][order_[axis][begin]];
        return {widestAxis(extent), (end - begin) / 2};
    }

    // Moves the split's left triangles to the front of the slice in all three orders.
    void partition(const ExactSplit& split, uint32_t begin, uint32_t end) {
        std::array<bool, kExactSubtreeSize> goesLeft;
        const uint32_t middle = begin + split.leftCount;
        for (uint32_t i = begin; i < end; ++i) goesLeft[order_[split.axis][i]] = i < middle;
        for (int axis = 0; axis < 3; ++axis) {
            if (axis == split.axis) continue;
            std::array<Slot, kExactSubtreeSize> right;
            uint32_t left = begin, rightCount = 0;
            // Written to both sides and kept on one, without branches: which side a
            // triangle goes to is as unpredictable as a coin toss.
            for (uint32_t i = begin; i < end; ++i) {
                Slot slot = order_[axis][i];
                order_[axis][left] = slot;
                right[rightCount] = slot;
                left += goesLeft[slot];
                rightCount += !goesLeft[slot];
            }
            std::copy_n(right.begin(), rightCount, &order_[axis][middle]);
        }
    }

    Bounds3 boundsOf(uint32_t begin, uint32_t end) const {
        Box4 box;
        for (uint32_t i = begin; i < end; ++i) box.extend(low_[order_[0][i]], high_[order_[0][i]]);
        return box.bounds();
    }

    std::span<TriangleBox> boxes_;
    uint32_t count_;
    std::array<TriangleBox, kExactSubtreeSize> records_;
    std::array<Float4, kExactSubtreeSize> low_, high_;  // records_' bounds, by slot
    std::array<std::array<Slot, kExactSubtreeSize>, 3> order_;  // per axis: slots by centroid
    std::array<std::array<float, kExactSubtreeSize>, 3> centroids_;  // per axis: records_' centroids, by slot
};

}  // namespace

void buildExactSubtree(std::span<TriangleBox> boxes, const BuildRange& range, uint32_t nodeIndex,
                       std::vector<BvhNode>& nodes) {
    ExactSubtree subtree(boxes.subspan(range.begin, range.size()));
    subtree.build(0, uint32_t(range.size()), range.depth, range.bounds, nodeIndex, range.begin, nodes);
    subtree.storeLeafOrder();
}

}  // namespace vkdr::bvh_build
