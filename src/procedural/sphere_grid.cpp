#include "procedural/sphere_grid.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vkdr {
namespace {

// Around 5000 triangles a sphere: round enough to look smooth, small enough that a
// 10M-triangle scene still has thousands of objects for the BVH to sort out.
constexpr double kTrianglesPerSphere = 5000.0;
constexpr float kBumpHeight = 0.06f;  // relative to the radius
constexpr float kBumpFrequency = 7.0f;

}  // namespace

SphereGrid::SphereGrid(uint64_t triangleBudget, float floorHalfSize, float maxRadius)
    : floorHalfSize_(floorHalfSize) {
    double budget = double(std::max<uint64_t>(triangleBudget, 8));
    spheresPerSide_ = uint32_t(std::max(1.0, std::round(std::sqrt(budget / kTrianglesPerSphere))));
    double perSphere = budget / double(sphereCount());
    // 2 * segments * (bands - 1) triangles, with twice as many segments as bands.
    uint32_t innerBands = uint32_t(std::max(1.0, std::round(std::sqrt(perSphere / 4.0))));
    bands_ = innerBands + 1;
    segments_ = uint32_t(std::max(3.0, std::round(perSphere / (2.0 * innerBands))));
    spacing_ = 2.0f * floorHalfSize / float(spheresPerSide_);
    radius_ = std::min(0.4f * spacing_, maxRadius);
}

void SphereGrid::sphereVertices(uint64_t sphere, std::vector<Vertex>& out) const {
    out.clear();
    float column = float(sphere % spheresPerSide_);
    float row = float(sphere / spheresPerSide_);
    glm::vec3 centre(-floorHalfSize_ + (column + 0.5f) * spacing_,
                     radius_ * (1.0f + kBumpHeight),
                     -floorHalfSize_ + (row + 0.5f) * spacing_);
    for (uint32_t b = 0; b <= bands_; ++b) {
        float theta = std::numbers::pi_v<float> * float(b) / float(bands_);  // 0 at the top pole
        for (uint32_t s = 0; s <= segments_; ++s) {
            float phi = 2.0f * std::numbers::pi_v<float> * float(s) / float(segments_);
            float bump = 1.0f + kBumpHeight * std::sin(kBumpFrequency * theta) *
                                    std::sin(kBumpFrequency * phi);
            glm::vec3 direction(std::sin(theta) * std::cos(phi), std::cos(theta),
                                std::sin(theta) * std::sin(phi));
            out.push_back({centre + radius_ * bump * direction,
                           {float(s) / float(segments_), float(b) / float(bands_)}});
        }
    }
}

void SphereGrid::sphereIndices(uint64_t sphere, std::vector<uint32_t>& out) const {
    out.clear();
    uint32_t first = uint32_t(sphere * verticesPerSphere());
    auto vertex = [&](uint32_t band, uint32_t segment) {
        return first + band * (segments_ + 1) + segment;
    };
    for (uint32_t b = 0; b < bands_; ++b) {
        for (uint32_t s = 0; s < segments_; ++s) {
            uint32_t upperLeft = vertex(b, s), upperRight = vertex(b, s + 1);
            uint32_t lowerLeft = vertex(b + 1, s), lowerRight = vertex(b + 1, s + 1);
            // At the poles one corner pair coincides: emit only the non-degenerate half.
            if (b != 0) {
                out.insert(out.end(), {upperLeft, upperRight, lowerRight});
            }
            if (b != bands_ - 1) {
                out.insert(out.end(), {upperLeft, lowerRight, lowerLeft});
            }
        }
    }
}

}  // namespace vkdr
