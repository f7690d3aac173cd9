#pragma once
// What the BVH builder's two split finders share: the per-triangle record, the node
// ranges, the SAH cost model and the four-float SIMD boxes. Internal to src/bvh.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include <glm/glm.hpp>

#include "bvh/bounds.h"
#include "bvh/bvh.h"

namespace vkdr::bvh_build {

// Cost of visiting an interior node relative to one triangle test: a visit tests the
// two children's boxes, about as much work as one triangle.
inline constexpr float kTraversalCost = 1.0f;

// The build's only per-triangle storage. Partitioning moves these records rather than
// indices to them, so every pass over a range reads memory in order.
struct TriangleBox {
    glm::vec3 min, max;  // the triangle's bounds
    uint32_t triangle;
    Bounds3 bounds() const { return {min, max}; }
    // Halved before adding so that huge coordinates cannot overflow to infinity.
    glm::vec3 centroid() const { return 0.5f * min + 0.5f * max; }
};
// load4() of either corner stays inside the record.
static_assert(sizeof(TriangleBox) == 28 && offsetof(TriangleBox, triangle) == 24);
// So that allocating a million of them writes nothing: the records are first written,
// and their pages first touched, by the parallel loop that fills them.
static_assert(std::is_trivially_default_constructible_v<TriangleBox>);

// boxes[begin, end): the triangles of one node, and what is known about them.
struct BuildRange {
    size_t begin = 0;
    size_t end = 0;
    uint32_t depth = 0;
    Bounds3 bounds;
    Bounds3 centroidBounds;
    size_t size() const { return end - begin; }
};

// Turns the summed count * area of both children into the SAH cost of the split.
inline float sahCost(float childCosts, float nodeArea) {
    // A node whose box has no area (collinear degenerate triangles) costs nothing to visit.
    return kTraversalCost + (nodeArea > 0.0f ? childCosts / nodeArea : 0.0f);
}

// ceil(log2(n)): the depth of a subtree of n triangles split at the median down to one.
inline uint32_t medianSplitDepth(size_t n) { return n <= 1 ? 0 : uint32_t(std::bit_width(n - 1)); }

// Whether a node at this depth can still hold n triangles without the tree exceeding
// kBvhMaxDepth: every node keeps this true, and median splits preserve it.
inline bool fitsDepthLimit(uint32_t depth, size_t n) { return depth + medianSplitDepth(n) <= kBvhMaxDepth; }

// The widest axis of a box (x before y before z on ties): median splits halve along it.
inline int widestAxis(const glm::vec3& extent) {
    return extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
}

// Four floats in one SIMD register (a GCC and Clang vector extension), for the
// build's inner loops: they update whole boxes at once. Lane 3 is unused.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = int32_t __attribute__((vector_size(16)));
using UInt4 = uint32_t __attribute__((vector_size(16)));

inline Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }
inline Float4 max4(Float4 a, Float4 b) { return a < b ? b : a; }
// Loads x, y, z, and 0 into lane 3. Lane 3 must not keep the bytes that follow v in
// memory: after boundsMax they are the triangle index, which as a float is a denormal,
// and arithmetic on denormals takes a microcode assist of ~100 cycles per operation.
// Clearing the lane with a mask is one instruction; inserting a 0 is three.
inline Float4 load4(const glm::vec3& v) {
    Float4 result;
    std::memcpy(&result, &v, sizeof(result));
    return Float4(Int4(result) & Int4{-1, -1, -1, 0});
}

// The centroid of a box given by its corners, with TriangleBox::centroid()'s
// arithmetic: binning, partitioning and sorting must all place a box alike.
inline Float4 centroid4(Float4 min, Float4 max) { return 0.5f * min + 0.5f * max; }

// Bounds3 in two SIMD registers, for the sweeps over candidate splits and the
// partitions, where converting to and from Bounds3 would cost more than the work.
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

// Half areas of three boxes, one per lane, with Bounds3::halfArea()'s arithmetic (so
// the same splits win); 0 for an empty box. Inlined: a call passes the boxes through memory.
[[gnu::always_inline]] inline Float4 halfAreas(const std::array<Box4, 3>& boxes) {
    Float4 d0 = boxes[0].max - boxes[0].min, d1 = boxes[1].max - boxes[1].min, d2 = boxes[2].max - boxes[2].min;
    Float4 x{d0[0], d1[0], d2[0], 0.0f}, y{d0[1], d1[1], d2[1], 0.0f}, z{d0[2], d1[2], d2[2], 0.0f};
    Int4 empty = (x < 0.0f) | (y < 0.0f) | (z < 0.0f);
    return empty ? Float4{} : x * y + y * z + z * x;
}

}  // namespace vkdr::bvh_build
