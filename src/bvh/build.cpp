#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "bvh/bounds.h"
#include "bvh/bvh.h"

namespace vkdr {
namespace {

// Small nodes, the great majority, get fewer bins: two per triangle are enough to
// tell most of them apart, and setting up and sweeping bins is a per-node cost.
constexpr int kMaxBinCount = 32;
// Cost of visiting an interior node relative to one triangle test: a visit tests the
// two children's boxes, about as much work as one triangle.
constexpr float kTraversalCost = 1.0f;
// Below these sizes, task overhead outweighs the work: ranges bin serially, and a
// right child is built by the task that built its parent.
constexpr size_t kParallelBinningSize = 64 * 1024;
constexpr size_t kParallelSubtreeSize = 4 * 1024;
constexpr size_t kBinningGrainSize = 16 * 1024;
// Keeps node indices (at most 2n - 1 nodes) within uint32_t.
constexpr size_t kMaxTriangles = size_t(1) << 31;

// The build's only per-triangle storage. Partitioning moves these records rather than
// indices to them, so every pass over a range reads memory in order.
struct TriangleBox {
    Bounds3 bounds;
    uint32_t triangle;
    // Halved before adding so that huge coordinates cannot overflow to infinity.
    glm::vec3 centroid() const { return 0.5f * bounds.min + 0.5f * bounds.max; }
};
// load4() of either corner stays inside the record.
static_assert(sizeof(TriangleBox) == 28 && offsetof(TriangleBox, triangle) == 24);

// boxes[begin, end): the triangles of one node, and what is known about them.
struct BuildRange {
    size_t begin = 0;
    size_t end = 0;
    uint32_t depth = 0;
    Bounds3 bounds;
    Bounds3 centroidBounds;
    size_t size() const { return end - begin; }
};

// Four floats in one SIMD register (a GCC and Clang vector extension), for the
// build's innermost loop, binning: it updates whole boxes at once. Lane 3 is unused.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = int32_t __attribute__((vector_size(16)));
using UInt4 = uint32_t __attribute__((vector_size(16)));

Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }
Float4 max4(Float4 a, Float4 b) { return a < b ? b : a; }
// Loads x, y, z, and 0 into lane 3. Lane 3 must not keep the bytes that follow v in
// memory: after boundsMax they are the triangle index, which as a float is a denormal,
// and arithmetic on denormals takes a microcode assist of ~100 cycles per operation.
Float4 load4(const glm::vec3& v) {
    Float4 result;
    std::memcpy(&result, &v, sizeof(result));
    result[3] = 0.0f;
    return result;
}

// Maps a centroid to one of binCount() equal slices of the centroid bounds, per axis.
class BinMapping {
public:
    explicit BinMapping(const BuildRange& range)
        : binCount_(int(std::min(size_t(kMaxBinCount), 2 * range.size()))), origin_(range.centroidBounds.min) {
        for (int axis = 0; axis < 3; ++axis) {
            float extent = range.centroidBounds.max[axis] - range.centroidBounds.min[axis];
            float scale = float(binCount_) / extent;
            scale_[axis] = extent > 0.0f && std::isfinite(scale) ? scale : 0.0f;
        }
    }
    int binCount() const { return binCount_; }
    // False where all centroids coincide (or are too close to tell apart).
    bool canSplit(int axis) const { return scale_[axis] > 0.0f; }
    bool canSplitAnyAxis() const { return canSplit(0) || canSplit(1) || canSplit(2); }
    int bin(const glm::vec3& centroid, int axis) const {
        float f = (centroid[axis] - origin_[axis]) * scale_[axis];
        return int(std::min(f, float(binCount_ - 1)));
    }
    // bin() for all three axes at once, with the same arithmetic.
    Int4 bins(Float4 centroid) const {
        Float4 f = (centroid - Float4{origin_.x, origin_.y, origin_.z, 0.0f}) * Float4{scale_.x, scale_.y, scale_.z, 0.0f};
        return __builtin_convertvector(min4(f, Float4{} + float(binCount_ - 1)), Int4);
    }

private:
    int binCount_;
    glm::vec3 origin_;  // no centroid lies below it, so bins are never negative
    glm::vec3 scale_;   // bins per unit length; 0 on an axis that cannot be split
};

// Trivially constructible, so that a BinGrid costs only the bins it uses.
struct Bin {
    Float4 min, max;
    uint32_t count;
};
static_assert(std::is_trivially_default_constructible_v<Bin>);

class BinGrid {
public:
    explicit BinGrid(const BinMapping& mapping) : binCount_(mapping.binCount()) {
        const float huge = std::numeric_limits<float>::max();
        for (auto& bins : axes_) std::fill_n(bins.begin(), binCount_, Bin{Float4{} + huge, Float4{} - huge, 0});
    }
    std::span<const Bin> bins(int axis) const { return {axes_[axis].data(), size_t(binCount_)}; }

    // Bins the box along all three axes; an axis that cannot be split gathers
    // everything in its bin 0, which findBestSplit ignores.
    void add(const TriangleBox& box, const BinMapping& mapping) {
        Float4 min = load4(box.bounds.min), max = load4(box.bounds.max);
        Int4 bins = mapping.bins(0.5f * min + 0.5f * max);  // as TriangleBox::centroid()
        for (int axis = 0; axis < 3; ++axis) {
            Bin& bin = axes_[axis][bins[axis]];
            bin.min = min4(bin.min, min);
            bin.max = max4(bin.max, max);
            ++bin.count;
        }
    }
    void merge(const BinGrid& other) {
        for (int axis = 0; axis < 3; ++axis)
            for (int i = 0; i < binCount_; ++i) {
                Bin& bin = axes_[axis][i];
                const Bin& more = other.axes_[axis][i];
                bin.min = min4(bin.min, more.min);
                bin.max = max4(bin.max, more.max);
                bin.count += more.count;
            }
    }

private:
    int binCount_;
    std::array<std::array<Bin, kMaxBinCount>, 3> axes_;
};

Bounds3 boundsOf(const Bin& bin) { return {{bin.min[0], bin.min[1], bin.min[2]}, {bin.max[0], bin.max[1], bin.max[2]}}; }

// Bounds3 in two SIMD registers, for the sweeps over bins and the partition: every
// node sweeps all its bins six times, and converting each bin to a Bounds3 cost more
// than the sweep itself.
struct Box4 {
    Float4 min = Float4{} + std::numeric_limits<float>::max();
    Float4 max = Float4{} - std::numeric_limits<float>::max();
    void extend(Float4 low, Float4 high) {
        min = min4(min, low);
        max = max4(max, high);
    }
    void extend(Float4 point) { extend(point, point); }
    // Bounds3::halfArea() with the same arithmetic, so the same splits win.
    float halfArea() const {
        Float4 d = max - min;
        if (d[0] < 0.0f || d[1] < 0.0f || d[2] < 0.0f) return 0.0f;
        return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    }
    Bounds3 bounds() const { return {{min[0], min[1], min[2]}, {max[0], max[1], max[2]}}; }
};

// Where to divide a node's triangles, and what that costs in triangle tests.
struct Split {
    int axis = -1;  // -1: no plane separates the triangles
    int bin = 0;    // binned splits: bins [0, bin) along axis go left
    uint32_t leftCount = 0, rightCount = 0;
    Bounds3 leftBounds, rightBounds;
    float cost = std::numeric_limits<float>::infinity();
};

// Turns the summed count * area of both sides into the SAH cost of the split.
float sahCost(float childCosts, const BuildRange& range) {
    // A node whose box has no area (collinear degenerate triangles) costs nothing to visit.
    float nodeArea = range.bounds.halfArea();
    return kTraversalCost + (nodeArea > 0.0f ? childCosts / nodeArea : 0.0f);
}

// Half areas of three boxes, one per lane, with Bounds3::halfArea()'s arithmetic (so
// the same splits win); 0 for an empty box. Inlined: a call passes the boxes through memory.
[[gnu::always_inline]] inline Float4 halfAreas(const std::array<Box4, 3>& boxes) {
    Float4 d0 = boxes[0].max - boxes[0].min, d1 = boxes[1].max - boxes[1].min, d2 = boxes[2].max - boxes[2].min;
    Float4 x{d0[0], d1[0], d2[0], 0.0f}, y{d0[1], d1[1], d2[1], 0.0f}, z{d0[2], d1[2], d2[2], 0.0f};
    Int4 empty = (x < 0.0f) | (y < 0.0f) | (z < 0.0f);
    return empty ? Float4{} : x * y + y * z + z * x;
}

// The SAH sweeps run the three axes at once, one per SIMD lane, without branches: a
// sweep is a chain of dependent min/max and area sums, too short per bin to keep a
// core busy one axis at a time. An empty bin changes neither side, so a plane after it
// costs what the plane before it did and never wins the strict comparison: the split
// chosen, ties included, is the one sweeping each axis alone would choose, axis 0 first.
Split findBestSplit(const BinGrid& grid, const BinMapping& mapping, const BuildRange& range) {
    const int binCount = mapping.binCount();
    std::array<std::span<const Bin>, 3> bins{grid.bins(0), grid.bins(1), grid.bins(2)};
    auto countsOf = [&](int i) { return UInt4{bins[0][i].count, bins[1][i].count, bins[2][i].count, 0}; };
    auto extend = [&](std::array<Box4, 3>& boxes, int i) {
        for (int axis = 0; axis < 3; ++axis) boxes[axis].extend(bins[axis][i].min, bins[axis][i].max);
    };
    // aboveCost[i]: count * area of the bins [i, binCount), per axis.
    std::array<Float4, kMaxBinCount> aboveCost;
    std::array<Box4, 3> above;
    UInt4 aboveCount{};
    for (int i = binCount - 1; i >= 1; --i) {
        extend(above, i);
        aboveCount += countsOf(i);
        aboveCost[i] = __builtin_convertvector(aboveCount, Float4) * halfAreas(above);
    }
    const Int4 splittable{-int(mapping.canSplit(0)), -int(mapping.canSplit(1)), -int(mapping.canSplit(2)), 0};
    const UInt4 total = UInt4{} + uint32_t(range.size());
    Float4 bestCost = Float4{} + std::numeric_limits<float>::infinity();
    Int4 bestBin{};
    std::array<Box4, 3> below;
    UInt4 belowCount{};
    for (int i = 1; i < binCount; ++i) {
        extend(below, i - 1);
        belowCount += countsOf(i - 1);
        Float4 cost = __builtin_convertvector(belowCount, Float4) * halfAreas(below) + aboveCost[i];
        // Both sides must hold triangles.
        Int4 wins = splittable & (belowCount > 0) & (belowCount < total) & (cost < bestCost);
        bestCost = wins ? cost : bestCost;
        bestBin = wins ? Int4{} + i : bestBin;
    }
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
        if (bestCost[axis] < best.cost) {
            best.axis = axis;
            best.bin = bestBin[axis];
            best.cost = bestCost[axis];
        }
    }
    if (best.axis < 0) return best;

    for (int i = 0; i < binCount; ++i) {
        const Bin& bin = bins[best.axis][i];
        (i < best.bin ? best.leftBounds : best.rightBounds).extend(boundsOf(bin));
        (i < best.bin ? best.leftCount : best.rightCount) += bin.count;
    }
    best.cost = sahCost(best.cost, range);
    return best;
}

// ceil(log2(n)): the depth of a subtree of n triangles split at the median down to one.
uint32_t medianSplitDepth(size_t n) { return n <= 1 ? 0 : uint32_t(std::bit_width(n - 1)); }

// Whether a node at this depth can still hold n triangles without the tree exceeding
// kBvhMaxDepth: every node keeps this true, and median splits preserve it.
bool fitsDepthLimit(uint32_t depth, size_t n) { return depth + medianSplitDepth(n) <= kBvhMaxDepth; }

// Moves a subtree built with its root at subtree[0] into nodes: the root to
// nodes[rootIndex], the rest appended, with child links shifted to match.
void appendSubtree(const std::vector<BvhNode>& subtree, uint32_t rootIndex, std::vector<BvhNode>& nodes) {
    uint32_t shift = uint32_t(nodes.size()) - 1;  // subtree[k], k >= 1, lands at nodes[shift + k]
    auto moved = [shift](BvhNode node) {
        if (node.count == 0) node.firstOrChild += shift;
        return node;
    };
    nodes[rootIndex] = moved(subtree[0]);
    for (size_t k = 1; k < subtree.size(); ++k) nodes.push_back(moved(subtree[k]));
}

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class Builder {
public:
    explicit Builder(std::span<TriangleBox> boxes) : boxes_(boxes) {}

    // Builds the subtree of range with its root at nodes[nodeIndex], appending the
    // rest of its nodes to nodes.
    void build(const BuildRange& range, uint32_t nodeIndex, std::vector<BvhNode>& nodes) const {
        std::optional<std::pair<BuildRange, BuildRange>> children = chooseChildren(range);
        if (!children) {
            nodes[nodeIndex] = {range.bounds.min, uint32_t(range.begin), range.bounds.max, uint32_t(range.size())};
            return;
        }
        const auto& [left, right] = *children;
        uint32_t firstChild = uint32_t(nodes.size());
        nodes.resize(nodes.size() + 2);
        nodes[nodeIndex] = {range.bounds.min, firstChild, range.bounds.max, 0};
        if (right.size() < kParallelSubtreeSize) {
            build(left, firstChild, nodes);
            build(right, firstChild + 1, nodes);
            return;
        }
        // The right subtree gets its own array, appended after both are done, so that
        // the node order does not depend on which task finishes first.
        std::vector<BvhNode> rightNodes;
        rightNodes.reserve(2 * right.size() - 1);  // the most a subtree can have: it never moves
        rightNodes.resize(1);
        tbb::parallel_invoke([&] { build(left, firstChild, nodes); }, [&] { build(right, 0, rightNodes); });
        appendSubtree(rightNodes, firstChild + 1, nodes);
    }

private:
    // The two children of range, or nothing when range should be a leaf.
    std::optional<std::pair<BuildRange, BuildRange>> chooseChildren(const BuildRange& range) const {
        if (range.size() <= 1) return std::nullopt;
        BinMapping mapping(range);
        Split split;
        if (mapping.canSplitAnyAxis()) split = findBestSplit(binTriangles(range, mapping), mapping, range);

        bool leafAllowed = range.size() <= kBvhMaxLeafTriangles;
        if (leafAllowed && !(split.cost < float(range.size()))) return std::nullopt;
        bool splitFits = split.axis >= 0 && fitsDepthLimit(range.depth + 1, split.leftCount) &&
                         fitsDepthLimit(range.depth + 1, split.rightCount);
        return splitFits ? partition(range, split, mapping) : splitAtMedian(range);
    }

    BinGrid binTriangles(const BuildRange& range, const BinMapping& mapping) const {
        return range.size() < kParallelBinningSize ? binSerially(range, mapping) : binInParallel(range, mapping);
    }

    BinGrid binSerially(const BuildRange& range, const BinMapping& mapping) const {
        BinGrid grid(mapping);
        for (size_t i = range.begin; i < range.end; ++i) grid.add(boxes_[i], mapping);
        return grid;
    }

    BinGrid binInParallel(const BuildRange& range, const BinMapping& mapping) const {
        // Counts add and bounds take min/max: exact, so any reduction order gives the same bins.
        return tbb::parallel_reduce(
            tbb::blocked_range<size_t>(range.begin, range.end, kBinningGrainSize), BinGrid(mapping),
            [&](const tbb::blocked_range<size_t>& r, BinGrid grid) {
                for (size_t i = r.begin(); i < r.end(); ++i) grid.add(boxes_[i], mapping);
                return grid;
            },
            [](BinGrid a, const BinGrid& b) {
                a.merge(b);
                return a;
            });
    }

    // Hoare partition that looks at each box once and gathers the children's centroid
    // bounds on the way; their bounds come from the bins.
    std::pair<BuildRange, BuildRange> partition(const BuildRange& range, const Split& split,
                                                const BinMapping& mapping) const {
        // As TriangleBox::centroid() and BinMapping::bin(), with the same arithmetic.
        auto centroidOf = [](const TriangleBox& box) {
            return 0.5f * load4(box.bounds.min) + 0.5f * load4(box.bounds.max);
        };
        auto goesLeft = [&](Float4 centroid) { return mapping.bins(centroid)[split.axis] < split.bin; };
        Box4 leftCentroids, rightCentroids;
        size_t i = range.begin, j = range.end;
        for (;;) {
            Float4 stray{}, strayFromRight{};
            while (i < j && goesLeft(stray = centroidOf(boxes_[i]))) {
                leftCentroids.extend(stray);
                ++i;
            }
            while (i < j && !goesLeft(strayFromRight = centroidOf(boxes_[j - 1]))) {
                rightCentroids.extend(strayFromRight);
                --j;
            }
            if (i == j) break;
            std::swap(boxes_[i++], boxes_[--j]);
            leftCentroids.extend(strayFromRight);
            rightCentroids.extend(stray);
        }
        BuildRange left{.depth = range.depth + 1, .bounds = split.leftBounds, .centroidBounds = leftCentroids.bounds()};
        BuildRange right{.depth = range.depth + 1, .bounds = split.rightBounds,
                         .centroidBounds = rightCentroids.bounds()};
        left.begin = range.begin;
        left.end = right.begin = i;
        right.end = range.end;
        return {left, right};
    }

    // Halves by count along the widest centroid axis; by index when the centroids
    // coincide. Used where the SAH cannot separate the triangles or would make the
    // tree too deep.
    std::pair<BuildRange, BuildRange> splitAtMedian(const BuildRange& range) const {
        glm::vec3 extent = range.centroidBounds.max - range.centroidBounds.min;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        size_t middle = range.begin + range.size() / 2;
        if (extent[axis] > 0.0f)
            std::nth_element(boxes_.begin() + range.begin, boxes_.begin() + middle, boxes_.begin() + range.end,
                             [axis](const TriangleBox& a, const TriangleBox& b) {
                                 return a.centroid()[axis] < b.centroid()[axis];
                             });
        return {describe(range.begin, middle, range.depth + 1), describe(middle, range.end, range.depth + 1)};
    }

    BuildRange describe(size_t begin, size_t end, uint32_t depth) const {
        BuildRange range{.begin = begin, .end = end, .depth = depth};
        for (size_t i = begin; i < end; ++i) {
            range.bounds.extend(boxes_[i].bounds);
            range.centroidBounds.extend(boxes_[i].centroid());
        }
        return range;
    }

    std::span<TriangleBox> boxes_;
};

// One box per triangle, with the root range's bounds gathered on the way.
std::vector<TriangleBox> boxTriangles(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                      BuildRange& root) {
    std::vector<TriangleBox> boxes(triangles.size());
    root = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, triangles.size()), BuildRange{},
        [&](const tbb::blocked_range<size_t>& r, BuildRange partial) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const glm::uvec3& triangle = triangles[i];
                if (std::max({triangle.x, triangle.y, triangle.z}) >= positions.size())
                    throw std::invalid_argument("buildBvh: triangle " + std::to_string(i) +
                                                " indexes a vertex past the " + std::to_string(positions.size()) +
                                                " positions");
                Bounds3 bounds;
                for (int k = 0; k < 3; ++k) bounds.extend(positions[triangle[k]]);
                // A non-finite vertex makes intersectTriangle reject the triangle, so it
                // can never be hit: an empty box keeps it out of every node's bounds.
                if (!isFinite(bounds.min) || !isFinite(bounds.max)) bounds = Bounds3{};
                boxes[i] = {bounds, uint32_t(i)};
                partial.bounds.extend(bounds);
                partial.centroidBounds.extend(boxes[i].centroid());
            }
            return partial;
        },
        [](BuildRange a, const BuildRange& b) {
            a.bounds.extend(b.bounds);
            a.centroidBounds.extend(b.centroidBounds);
            return a;
        });
    root.begin = 0;
    root.end = triangles.size();
    root.depth = 0;
    return boxes;
}

}  // namespace

Bvh buildBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles) {
    if (triangles.size() > kMaxTriangles)
        throw std::invalid_argument("buildBvh: " + std::to_string(triangles.size()) + " triangles, at most " +
                                    std::to_string(kMaxTriangles) + " supported");
    Bvh bvh;
    if (triangles.empty()) {
        Bounds3 empty;
        bvh.nodes.push_back({empty.min, 0, empty.max, 0});
        return bvh;
    }
    BuildRange root;
    std::vector<TriangleBox> boxes = boxTriangles(positions, triangles, root);
    bvh.nodes.reserve(2 * triangles.size() - 1);  // pages the tree does not use are never touched
    bvh.nodes.resize(1);
    Builder(boxes).build(root, 0, bvh.nodes);
    bvh.nodes.shrink_to_fit();

    bvh.triangleOrder.resize(boxes.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, boxes.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) bvh.triangleOrder[i] = boxes[i].triangle;
    });
    return bvh;
}

}  // namespace vkdr
