#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "bvh/bounds.h"
#include "bvh/bvh.h"
#include "test_meshes.h"

namespace vkdr {
namespace {

using test::Mesh;

Bounds3 nodeBounds(const BvhNode& node) { return {node.boundsMin, node.boundsMax}; }

Bounds3 triangleBounds(const Mesh& mesh, uint32_t triangle) {
    Bounds3 bounds;
    for (int k = 0; k < 3; ++k) bounds.extend(mesh.positions[mesh.triangles[triangle][k]]);
    return bounds;
}

Bvh build(const Mesh& mesh) { return buildBvh(mesh.positions, mesh.triangles); }

// Walks the tree from the root and checks every invariant of the layout in bvh.h.
void expectWellFormed(const Bvh& bvh, const Mesh& mesh) {
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_EQ(bvh.triangleOrder.size(), mesh.triangles.size());
    std::vector<int> timesListed(mesh.triangles.size(), 0);
    for (uint32_t triangle : bvh.triangleOrder) {
        ASSERT_LT(triangle, mesh.triangles.size());
        ++timesListed[triangle];
    }
    EXPECT_TRUE(std::all_of(timesListed.begin(), timesListed.end(), [](int n) { return n == 1; }))
        << "every triangle appears exactly once in triangleOrder";

    struct Visit {
        uint32_t node;
        uint32_t depth;
    };
    std::vector<Visit> pending{{0, 0}};
    std::vector<int> timesVisited(bvh.nodes.size(), 0);
    std::vector<int> timesInLeaf(mesh.triangles.size(), 0);
    while (!pending.empty()) {
        auto [index, depth] = pending.back();
        pending.pop_back();
        ASSERT_LT(index, bvh.nodes.size());
        ASSERT_EQ(++timesVisited[index], 1) << "node " << index << " reached twice";
        ASSERT_LE(depth, kBvhMaxDepth);
        const BvhNode& node = bvh.nodes[index];
        if (node.count > 0) {
            ASSERT_LE(node.count, kBvhMaxLeafTriangles);
            ASSERT_LE(size_t(node.firstOrChild) + node.count, bvh.triangleOrder.size());
            for (uint32_t i = node.firstOrChild; i < node.firstOrChild + node.count; ++i) {
                ++timesInLeaf[i];
                Bounds3 bounds = triangleBounds(mesh, bvh.triangleOrder[i]);
                if (std::isfinite(bounds.halfArea())) {
                    EXPECT_TRUE(nodeBounds(node).contains(bounds)) << "leaf " << index << " triangle " << i;
                }
            }
            continue;
        }
        ASSERT_GT(node.firstOrChild, index) << "children come after their parent";
        ASSERT_LT(size_t(node.firstOrChild) + 1, bvh.nodes.size());
        for (uint32_t child = node.firstOrChild; child <= node.firstOrChild + 1; ++child) {
            EXPECT_TRUE(nodeBounds(node).contains(nodeBounds(bvh.nodes[child])))
                << "child " << child << " of " << index;
            pending.push_back({child, depth + 1});
        }
    }
    EXPECT_TRUE(std::all_of(timesVisited.begin(), timesVisited.end(), [](int n) { return n == 1; }))
        << "every node is reachable from the root exactly once";
    EXPECT_TRUE(std::all_of(timesInLeaf.begin(), timesInLeaf.end(), [](int n) { return n == 1; }))
        << "leaves cover triangleOrder without overlap";
}

uint32_t treeDepth(const Bvh& bvh, uint32_t node = 0) {
    const BvhNode& n = bvh.nodes[node];
    if (n.count > 0) return 0;
    return 1 + std::max(treeDepth(bvh, n.firstOrChild), treeDepth(bvh, n.firstOrChild + 1));
}

// Expected cost of a random ray that hits the root, in triangle tests, counting an
// interior node as 0.5 and a triangle as 1.
float sahCost(const Bvh& bvh) {
    float rootArea = nodeBounds(bvh.nodes[0]).halfArea();
    double cost = 0.0;
    for (const BvhNode& node : bvh.nodes)
        cost += nodeBounds(node).halfArea() / rootArea * (node.count > 0 ? float(node.count) : 0.5f);
    return float(cost);
}

// The baseline: halve by count along the widest axis down to 4 triangles per leaf.
Bvh buildMedianSplit(const Mesh& mesh) {
    Bvh bvh;
    bvh.triangleOrder.resize(mesh.triangles.size());
    for (uint32_t i = 0; i < bvh.triangleOrder.size(); ++i) bvh.triangleOrder[i] = i;
    auto centroid = [&](uint32_t t) {
        Bounds3 b = triangleBounds(mesh, t);
        return 0.5f * (b.min + b.max);
    };
    auto buildNode = [&](auto& self, uint32_t nodeIndex, uint32_t begin, uint32_t end) -> void {
        Bounds3 bounds, centroids;
        for (uint32_t i = begin; i < end; ++i) {
            bounds.extend(triangleBounds(mesh, bvh.triangleOrder[i]));
            centroids.extend(centroid(bvh.triangleOrder[i]));
        }
        if (end - begin <= 4) {
            bvh.nodes[nodeIndex] = {bounds.min, begin, bounds.max, end - begin};
            return;
        }
        glm::vec3 extent = centroids.max - centroids.min;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        uint32_t middle = (begin + end) / 2;
        std::nth_element(bvh.triangleOrder.begin() + begin, bvh.triangleOrder.begin() + middle,
                         bvh.triangleOrder.begin() + end,
                         [&](uint32_t a, uint32_t b) { return centroid(a)[axis] < centroid(b)[axis]; });
        uint32_t firstChild = uint32_t(bvh.nodes.size());
        bvh.nodes.resize(bvh.nodes.size() + 2);
        bvh.nodes[nodeIndex] = {bounds.min, firstChild, bounds.max, 0};
        self(self, firstChild, begin, middle);
        self(self, firstChild + 1, middle, end);
    };
    bvh.nodes.resize(1);
    buildNode(buildNode, 0, 0, uint32_t(mesh.triangles.size()));
    return bvh;
}

bool identical(const Bvh& a, const Bvh& b) {
    return a.triangleOrder == b.triangleOrder && a.nodes.size() == b.nodes.size() &&
           std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)) == 0;
}

TEST(BuildBvh, NoTrianglesGivesAnEmptyRootThatNoRayEnters) {
    Bvh bvh = buildBvh({}, {});
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_TRUE(bvh.triangleOrder.empty());
    EXPECT_EQ(bvh.nodes[0].count, 0u);
    EXPECT_TRUE(nodeBounds(bvh.nodes[0]).empty());
    EXPECT_FALSE(closestHit(bvh, {}, {}, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 1e30f));
}

TEST(BuildBvh, OneTriangleIsALeaf) {
    Mesh mesh;
    mesh.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    Bvh bvh = build(mesh);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].count, 1u);
    EXPECT_EQ(bvh.nodes[0].boundsMin, glm::vec3(0, 0, 0));
    EXPECT_EQ(bvh.nodes[0].boundsMax, glm::vec3(1, 1, 0));
    expectWellFormed(bvh, mesh);
}

TEST(BuildBvh, RandomSoupIsWellFormed) {
    Mesh mesh = test::randomSoup(20000, 0.02f, 1);
    expectWellFormed(build(mesh), mesh);
}

TEST(BuildBvh, GridWithSharedVerticesIsWellFormed) {
    Mesh mesh = test::gridMesh(100);
    expectWellFormed(build(mesh), mesh);
}

TEST(BuildBvh, DegenerateTrianglesAreKept) {
    Mesh mesh = test::randomSoup(1000, 0.05f, 2);
    test::addDegenerateTriangles(mesh, 1000, 3);
    expectWellFormed(build(mesh), mesh);
}

TEST(BuildBvh, CoincidentCentroidsSplitByCountIntoSmallLeaves) {
    Mesh mesh;
    for (int i = 0; i < 1000; ++i) mesh.addTriangle({-1, -1, 0}, {1, -1, 0}, {0, 2, 0});
    // Different shapes, same centroid of bounds.
    for (int i = 0; i < 1000; ++i) mesh.addTriangle({-1, 0, -1}, {1, 0, 1}, {0, 0, 0});
    Bvh bvh = build(mesh);
    expectWellFormed(bvh, mesh);
    EXPECT_LE(treeDepth(bvh), 10u);
}

TEST(BuildBvh, NonFiniteVerticesDoNotWidenTheBounds) {
    Mesh mesh = test::randomSoup(100, 0.05f, 4);
    float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    mesh.addTriangle({nan, 0, 0}, {1, 0, 0}, {0, 1, 0});
    mesh.addTriangle({inf, 0, 0}, {1, 0, 0}, {0, 1, 0});
    Bvh bvh = build(mesh);
    expectWellFormed(bvh, mesh);
    EXPECT_TRUE(Bounds3({glm::vec3(-1.0f), glm::vec3(2.0f)}).contains(nodeBounds(bvh.nodes[0])));
}

TEST(BuildBvh, PathologicalSizesStayWithinTheDepthLimit) {
    // Each triangle much larger than the previous one: the SAH alone would peel
    // one triangle off per level.
    Mesh mesh;
    for (int i = 0; i < 400; ++i) {
        float s = std::pow(1.2f, float(i)) * 1e-30f;
        mesh.addTriangle({s, 0, 0}, {2 * s, s, 0}, {s, 0, s});
    }
    Bvh bvh = build(mesh);
    expectWellFormed(bvh, mesh);
    EXPECT_LE(treeDepth(bvh), kBvhMaxDepth);
}

TEST(BuildBvh, OutOfRangeVertexIndexThrows) {
    Mesh mesh;
    mesh.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    mesh.triangles[0].z = 3;
    EXPECT_THROW(build(mesh), std::invalid_argument);
}

TEST(BuildBvh, SameTreeWhateverTheThreadCount) {
    Mesh mesh = test::randomSoup(300000, 0.01f, 5);
    test::addDegenerateTriangles(mesh, 1000, 6);
    Bvh parallel = build(mesh);
    expectWellFormed(parallel, mesh);  // large enough that its top nodes bin a sample
    EXPECT_TRUE(identical(parallel, build(mesh)));
    tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_TRUE(identical(parallel, build(mesh)));
}

uint32_t trianglesUnder(const Bvh& bvh, uint32_t node) {
    const BvhNode& n = bvh.nodes[node];
    return n.count > 0 ? n.count : trianglesUnder(bvh, n.firstOrChild) + trianglesUnder(bvh, n.firstOrChild + 1);
}

// Small meshes are split exactly: the root's split must cost no more than every way of
// dividing the triangles sorted by centroid along an axis, found here by brute force.
TEST(BuildBvh, SmallMeshRootTakesTheCheapestSortedSplit) {
    for (uint32_t seed = 20; seed < 30; ++seed) {
        Mesh mesh = test::randomSoup(48, 0.05f + 0.01f * float(seed - 20), seed);
        const uint32_t n = uint32_t(mesh.triangles.size());
        double cheapest = std::numeric_limits<double>::infinity();
        for (int axis = 0; axis < 3; ++axis) {
            std::vector<uint32_t> order(n);
            for (uint32_t i = 0; i < n; ++i) order[i] = i;
            auto centroid = [&](uint32_t t) {
                Bounds3 b = triangleBounds(mesh, t);
                return 0.5f * b.min[axis] + 0.5f * b.max[axis];
            };
            std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return centroid(a) < centroid(b); });
            for (uint32_t k = 1; k < n; ++k) {
                Bounds3 left, right;
                for (uint32_t i = 0; i < n; ++i) (i < k ? left : right).extend(triangleBounds(mesh, order[i]));
                cheapest = std::min(cheapest, double(k) * left.halfArea() + double(n - k) * right.halfArea());
            }
        }
        Bvh bvh = build(mesh);
        ASSERT_EQ(bvh.nodes[0].count, 0u) << "seed " << seed;
        uint32_t first = bvh.nodes[0].firstOrChild;
        double rootSplit = double(trianglesUnder(bvh, first)) * nodeBounds(bvh.nodes[first]).halfArea() +
                           double(trianglesUnder(bvh, first + 1)) * nodeBounds(bvh.nodes[first + 1]).halfArea();
        // Single-precision sums of up to 48 areas: a relative 1e-5 is rounding, not a worse split.
        EXPECT_LE(rootSplit, cheapest * (1.0 + 1e-5)) << "seed " << seed;
        expectWellFormed(bvh, mesh);
    }
}

TEST(BuildBvh, SahCostBeatsMedianSplit) {
    // Clustered geometry, where the choice of split matters.
    Mesh mesh = test::randomSoup(20000, 0.002f, 7);
    for (glm::vec3& p : mesh.positions) p = p * p * p;
    Mesh large = test::randomSoup(200, 0.3f, 8);
    for (const glm::uvec3& t : large.triangles)
        mesh.addTriangle(large.positions[t.x], large.positions[t.y], large.positions[t.z]);

    float sah = sahCost(build(mesh)), median = sahCost(buildMedianSplit(mesh));
    std::printf("SAH cost: binned SAH %.1f, median split %.1f\n", sah, median);
    EXPECT_LT(sah, 0.9f * median);
}

}  // namespace
}  // namespace vkdr
