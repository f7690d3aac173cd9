#include <algorithm>
#include <limits>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "bvh/bvh.h"
#include "test_meshes.h"

namespace vkdr {
namespace {

using test::Mesh;

constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::optional<RayHit> bruteForceHit(const Mesh& mesh, const glm::vec3& o, const glm::vec3& d, float tMax) {
    std::optional<RayHit> closest;
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3& v = mesh.triangles[i];
        if (auto hit = intersectTriangle(o, d, mesh.positions[v.x], mesh.positions[v.y], mesh.positions[v.z], tMax)) {
            closest = *hit;
            closest->triangle = i;
            tMax = hit->t;
        }
    }
    return closest;
}

// Compares the BVH against every triangle. The same formula runs on the same inputs,
// so distances must agree exactly; where two triangles tie (a shared edge), either
// one is right.
class ClosestHitVsBruteForce {
public:
    explicit ClosestHitVsBruteForce(Mesh mesh) : mesh_(std::move(mesh)), bvh_(buildBvh(mesh_.positions, mesh_.triangles)) {}

    void expectSame(const glm::vec3& o, const glm::vec3& d, float tMax = kInfinity) {
        std::optional<RayHit> expected = bruteForceHit(mesh_, o, d, tMax);
        std::optional<RayHit> actual = closestHit(bvh_, mesh_.positions, mesh_.triangles, o, d, tMax);
        ++rays_;
        hits_ += expected.has_value();
        ASSERT_EQ(actual.has_value(), expected.has_value()) << "ray " << rays_;
        if (!expected) return;
        ASSERT_EQ(actual->t, expected->t) << "ray " << rays_;
        if (actual->triangle != expected->triangle) return;
        EXPECT_EQ(actual->b1, expected->b1);
        EXPECT_EQ(actual->b2, expected->b2);
    }
    int hits() const { return hits_; }
    int rays() const { return rays_; }

private:
    Mesh mesh_;
    Bvh bvh_;
    int rays_ = 0;
    int hits_ = 0;
};

glm::vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<float> normal;
    return glm::vec3(normal(rng), normal(rng), normal(rng));
}

TEST(IntersectTriangle, HitsFrontAndBackWithBarycentrics) {
    glm::vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0);
    auto front = intersectTriangle({0.25f, 0.5f, 1}, {0, 0, -2}, v0, v1, v2, kInfinity);
    ASSERT_TRUE(front);
    EXPECT_FLOAT_EQ(front->t, 0.5f);
    EXPECT_FLOAT_EQ(front->b1, 0.25f);
    EXPECT_FLOAT_EQ(front->b2, 0.5f);
    auto back = intersectTriangle({0.25f, 0.5f, -1}, {0, 0, 1}, v0, v1, v2, kInfinity);
    ASSERT_TRUE(back);
    EXPECT_FLOAT_EQ(back->t, 1.0f);
}

TEST(IntersectTriangle, MissesOutsideBehindBeyondAndParallel) {
    glm::vec3 v0(0, 0, 0), v1(1, 0, 0), v2(0, 1, 0);
    EXPECT_FALSE(intersectTriangle({0.75f, 0.5f, 1}, {0, 0, -1}, v0, v1, v2, kInfinity));  // outside
    EXPECT_FALSE(intersectTriangle({0.25f, 0.25f, -1}, {0, 0, -1}, v0, v1, v2, kInfinity));  // behind
    EXPECT_FALSE(intersectTriangle({0.25f, 0.25f, 1}, {0, 0, -1}, v0, v1, v2, 1.0f));  // t == tMax
    EXPECT_FALSE(intersectTriangle({0.25f, 0.25f, 0}, {0, 0, -1}, v0, v1, v2, kInfinity));  // t == 0
    EXPECT_FALSE(intersectTriangle({-1, 0.25f, 0}, {1, 0, 0}, v0, v1, v2, kInfinity));  // in its plane
    EXPECT_FALSE(intersectTriangle({0.25f, 0.25f, 1}, {0, 0, -1}, v0, v0, v2, kInfinity));  // degenerate
}

// Watertight: a ray aimed at a point on an edge that two triangles share meets one of
// them, whatever the rounding (Moller-Trumbore let 6 % of these rays pass between them,
// as it would through a closed medium boundary).
TEST(IntersectTriangle, NoRayPassesBetweenTrianglesThatShareAnEdge) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Mesh mesh = test::gridMesh(16);
    for (glm::vec3& p : mesh.positions) p.z = 0.3f * p.x + 0.2f * p.y;  // a tilted plane: no silhouettes
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
        // A cell's first triangle; its first and last corners span the diagonal it shares.
        const glm::uvec3& tri = mesh.triangles[2 * size_t(unit(rng) * float(mesh.triangles.size() / 2 - 1))];
        const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.z];
        const glm::vec3 target = a + unit(rng) * (b - a);
        const glm::vec3 origin(unit(rng) * 3.0f - 1.0f, unit(rng) * 3.0f - 1.0f, 1.0f + unit(rng));
        if (!bruteForceHit(mesh, origin, target - origin, 2.0f)) ++misses;
    }
    EXPECT_EQ(misses, 0);
}

TEST(ClosestHit, RandomRaysThroughARandomSoup) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-0.2f, 1.2f);
    ClosestHitVsBruteForce check(test::randomSoup(3000, 0.05f, 12));
    for (int i = 0; i < 5000; ++i) {
        // Origins inside the scene start inside many boxes.
        glm::vec3 o(unit(rng), unit(rng), unit(rng));
        check.expectSame(o, randomDirection(rng));
    }
    EXPECT_GT(check.hits(), check.rays() / 4);
}

TEST(ClosestHit, RaysLimitedByTMax) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    ClosestHitVsBruteForce check(test::randomSoup(3000, 0.05f, 14));
    for (int i = 0; i < 3000; ++i) check.expectSame({unit(rng), unit(rng), unit(rng)}, randomDirection(rng), 0.2f * unit(rng));
}

TEST(ClosestHit, SoupWithDegenerateTriangles) {
    std::mt19937 rng(15);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Mesh mesh = test::randomSoup(1000, 0.05f, 16);
    test::addDegenerateTriangles(mesh, 1000, 17);
    ClosestHitVsBruteForce check(std::move(mesh));
    for (int i = 0; i < 3000; ++i) check.expectSame({unit(rng), unit(rng), unit(rng)}, randomDirection(rng));
}

TEST(ClosestHit, GridThroughVerticesAndSharedEdges) {
    std::mt19937 rng(18);
    std::uniform_int_distribution<int> cell(0, 32);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    ClosestHitVsBruteForce check(test::gridMesh(32));
    for (int i = 0; i < 3000; ++i) {
        // Aim at grid vertices and edge midpoints, where neighbouring triangles meet.
        glm::vec3 target(cell(rng) / 32.0f, std::min(cell(rng) + 0.5f * float(i % 2), 32.0f) / 32.0f, 0.0f);
        glm::vec3 o(unit(rng), unit(rng), i % 3 == 0 ? -1.0f : 1.0f);
        check.expectSame(o, target - o);
    }
    // Moller-Trumbore is not watertight: a ray exactly through an edge or vertex may
    // slip between the triangles there (the BVH must then miss it too).
    EXPECT_GT(check.hits(), check.rays() * 99 / 100);
}

TEST(ClosestHit, AxisAlignedRaysWithSignedZeros) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
    Mesh mesh = test::randomSoup(2000, 0.05f, 20);
    Mesh grid = test::gridMesh(16);
    for (const glm::uvec3& t : grid.triangles) mesh.addTriangle(grid.positions[t.x], grid.positions[t.y], grid.positions[t.z]);
    ClosestHitVsBruteForce check(std::move(mesh));
    for (int i = 0; i < 3000; ++i) {
        int axis = i % 3;
        glm::vec3 d(0.0f);
        d[axis] = i % 2 ? 1.0f : -1.0f;
        // -0 gives 1/d = -inf: the box test must treat it like +0.
        d[(axis + 1) % 3] = -0.0f;
        glm::vec3 o(unit(rng), unit(rng), unit(rng));
        // Also rays exactly in the grid's plane and on cell boundaries, where
        // 0 * inf = NaN turns up in the slab test.
        if (i % 4 == 0) o.z = 0.0f;
        if (i % 5 == 0) o[(axis + 1) % 3] = float(i % 17) / 16.0f;
        check.expectSame(o, d);
    }
    EXPECT_GT(check.hits(), 0);
}

TEST(ClosestHit, RayAlongAFlatBoxPlaneHitsTheTriangleItCrosses) {
    // The grid's box has zero thickness in z; a ray in that plane crosses it at
    // 0 * inf, and must still find the triangle standing on the grid.
    Mesh mesh = test::gridMesh(4);
    mesh.addTriangle({0.5f, 0.2f, -0.5f}, {0.5f, 0.8f, -0.5f}, {0.5f, 0.5f, 0.5f});
    Bvh bvh = buildBvh(mesh.positions, mesh.triangles);
    auto hit = closestHit(bvh, mesh.positions, mesh.triangles, {-1.0f, 0.5f, 0.0f}, {1.0f, 0.0f, 0.0f}, kInfinity);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->triangle, mesh.triangles.size() - 1);
    EXPECT_FLOAT_EQ(hit->t, 1.5f);
}

TEST(ClosestHit, LargeSceneAgainstBruteForce) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    // Large enough for the parallel build paths.
    ClosestHitVsBruteForce check(test::randomSoup(100000, 0.01f, 22));
    for (int i = 0; i < 300; ++i) check.expectSame({unit(rng), unit(rng), unit(rng)}, randomDirection(rng));
}

}  // namespace
}  // namespace vkdr
