#pragma once
#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

namespace vkdr {

// Per-axis min and max, by value: std::min returns a reference, which GCC turns into
// branches and conditional loads, and glm::min calls through a function pointer.
// Together they were the largest cost of the BVH build.
inline float minOf(float a, float b) { return b < a ? b : a; }
inline float maxOf(float a, float b) { return a < b ? b : a; }
inline glm::vec3 minPerAxis(const glm::vec3& a, const glm::vec3& b) {
    return {minOf(a.x, b.x), minOf(a.y, b.y), minOf(a.z, b.z)};
}
inline glm::vec3 maxPerAxis(const glm::vec3& a, const glm::vec3& b) {
    return {maxOf(a.x, b.x), maxOf(a.y, b.y), maxOf(a.z, b.z)};
}

// Axis-aligned box. The default box is empty (min > max), so that extending it by
// anything gives exactly that thing's bounds.
struct Bounds3 {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    void extend(const glm::vec3& p) {
        min = minPerAxis(min, p);
        max = maxPerAxis(max, p);
    }
    void extend(const Bounds3& b) {
        min = minPerAxis(min, b.min);
        max = maxPerAxis(max, b.max);
    }
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    bool contains(const Bounds3& b) const {
        return glm::all(glm::lessThanEqual(min, b.min)) && glm::all(glm::lessThanEqual(b.max, max));
    }
    // Half the surface area: the SAH only ever compares ratios of areas.
    float halfArea() const {
        if (empty()) return 0.0f;
        glm::vec3 d = max - min;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
};

}  // namespace vkdr
