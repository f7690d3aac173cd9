// The intersect stage's BVH traversal against brute force over every triangle, on
// random rays through a random triangle soup and a closed mesh with shared edges.
#include <random>

#include "bvh/bvh.h"
#include "device_types.h"
#include "render/gpu_scene.h"
#include "render/push_constants.h"
#include "render/stage_pipelines.h"
#include "render_test_support.h"
#include "test_gltf.h"
#include "vk/commands.h"

namespace vkdr::test {
namespace {

Scene soupScene(int triangles, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Scene scene;
    for (int t = 0; t < triangles; ++t) {
        glm::vec3 centre(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) {
            scene.positions.push_back(centre + 0.15f * glm::vec3(u(rng), u(rng), u(rng)));
        }
        scene.triangles.push_back(glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2));
    }
    TestMesh ball = sphere(glm::vec3(0.2f, -0.1f, 0.3f), 0.6f, 3, 0);
    uint32_t base = static_cast<uint32_t>(scene.positions.size());
    scene.positions.insert(scene.positions.end(), ball.positions.begin(), ball.positions.end());
    for (const glm::uvec3& tri : ball.triangles) {
        scene.triangles.push_back(tri + base);
    }
    scene.materials.push_back(Material{.name = "grey"});
    scene.triangleMaterial.assign(scene.triangles.size(), 0);
    scene.triangleOutsideMedium.assign(scene.triangles.size(), kNoMedium);
    return scene;
}

class GpuTraversalTest : public RenderTest {};

// The intersect stage's hits (t, b1, b2, BVH-order triangle) of rays whose origins' w
// names the triangle each leaves (storeRay), or kNoHit.
std::vector<glm::vec4> traceRays(const GpuScene& gpuScene, const std::vector<glm::vec4>& origins,
                                 const std::vector<glm::vec4>& directions) {
    VulkanContext& context = testContext();
    const uint32_t rays = uint32_t(origins.size());
    std::vector<uint32_t> queueItems(gpu::kQueueCount * rays);
    for (uint32_t i = 0; i < rays; ++i) {
        queueItems[i] = i;
    }
    gpu::QueueCountersData counters{};
    counters.counts[gpu::kQueueRays0] = rays;
    Buffer originBuffer = uploadVector<glm::vec4>(context, origins, "origins");
    Buffer directionBuffer = uploadVector<glm::vec4>(context, directions, "directions");
    Buffer hitBuffer(context, rays * sizeof(glm::vec4), MemoryUse::Device, "hits");
    Buffer itemBuffer = uploadVector<uint32_t>(context, queueItems, "queue items");
    Buffer counterBuffer = uploadBuffer(context, std::as_bytes(std::span(&counters, 1)), "counters");

    gpu::RenderParams params{};
    params.triangleVertices = gpuScene.triangleVertices.address();
    params.bvhNodes = gpuScene.bvhNodes.address();
    params.rayOrigin = originBuffer.address();
    params.rayDirection = directionBuffer.address();
    params.hit = hitBuffer.address();
    params.queueItems = itemBuffer.address();
    params.queueCounters = counterBuffer.address();
    params.pathCapacity = rays;
    Buffer paramBuffer = uploadBuffer(context, std::as_bytes(std::span(&params, 1)), "params");

    StagePipelines pipelines(context, MediaFeatures{});
    PushConstants push{paramBuffer.address(), gpu::PassConstants{}};
    push.pass.currentRays = gpu::kQueueRays0;
    CommandRecorder recorder(context);
    recorder.dispatch(pipelines.intersect, rays, push.bytes());
    recorder.submitAndWait();
    std::vector<glm::vec4> hits(rays);
    downloadBuffer(context, hitBuffer, std::as_writable_bytes(std::span(hits)));
    std::vector<gpu::QueueCountersData> after(1);
    downloadBuffer(context, counterBuffer, std::as_writable_bytes(std::span(after)));
    EXPECT_EQ(after[0].truncatedLoops, 0u);
    return hits;
}

// The closest of the scene's triangles but `skipped` (an index of the scene's) by brute force.
std::optional<RayHit> bruteForceHit(const Scene& scene, glm::vec3 origin, glm::vec3 direction, uint32_t skipped) {
    std::optional<RayHit> best;
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
        const glm::uvec3& tri = scene.triangles[t];
        auto h = intersectTriangle(origin, direction, scene.positions[tri.x], scene.positions[tri.y],
                                   scene.positions[tri.z], best ? best->t : 1e30f);
        if (h && t != skipped) {
            best = h;
            best->triangle = t;
        }
    }
    return best;
}

// Each ray's hit against brute force: the same t, and the same triangle or one at that t
// (a ray through a shared edge may pick either). Returns how many hit.
int expectBruteForceHits(const Scene& scene, const Bvh& bvh, const std::vector<glm::vec4>& origins,
                         const std::vector<glm::vec4>& directions, const std::vector<glm::vec4>& hits) {
    int hitCount = 0;
    for (uint32_t i = 0; i < origins.size(); ++i) {
        const uint32_t leaves = glm::floatBitsToUint(origins[i].w);
        const uint32_t skipped = leaves == gpu::kNoHit ? gpu::kNoHit : bvh.triangleOrder[leaves];
        std::optional<RayHit> best = bruteForceHit(scene, glm::vec3(origins[i]), glm::vec3(directions[i]), skipped);
        uint32_t gpuTriangle = glm::floatBitsToUint(hits[i].w);
        if (!best) {
            EXPECT_EQ(gpuTriangle, gpu::kNoHit) << "ray " << i;
            continue;
        }
        ++hitCount;
        EXPECT_NE(gpuTriangle, gpu::kNoHit) << "ray " << i;
        if (gpuTriangle == gpu::kNoHit) {
            continue;
        }
        EXPECT_NE(gpuTriangle, leaves) << "ray " << i;
        EXPECT_NEAR(hits[i].x, best->t, 1e-5f * std::max(1.0f, best->t)) << "ray " << i;
        if (std::abs(hits[i].x - best->t) > 1e-5f) {
            continue;
        }
        uint32_t triangle = bvh.triangleOrder[gpuTriangle];
        if (triangle != best->triangle) {
            const glm::uvec3& tri = scene.triangles[triangle];
            auto h = intersectTriangle(glm::vec3(origins[i]), glm::vec3(directions[i]), scene.positions[tri.x],
                                       scene.positions[tri.y], scene.positions[tri.z], 1e30f);
            EXPECT_TRUE(h.has_value()) << "ray " << i;
            if (h) {
                EXPECT_NEAR(h->t, best->t, 1e-6f * std::max(1.0f, best->t)) << "ray " << i;
            }
        }
    }
    return hitCount;
}

TEST_F(GpuTraversalTest, ClosestHitMatchesBruteForce) {
    std::mt19937 rng(12345);
    Scene scene = soupScene(3000, rng);
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    GpuScene gpuScene = uploadScene(testContext(), scene, bvh);

    constexpr uint32_t kRays = 8192;
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    std::vector<glm::vec4> origins(kRays), directions(kRays);
    for (uint32_t i = 0; i < kRays; ++i) {
        origins[i] = glm::vec4(u(rng), u(rng), u(rng), glm::uintBitsToFloat(gpu::kNoHit));
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (i % 7 == 0) {
            d = glm::vec3(0.0f, 0.0f, 1.0f);  // axis-aligned: zero direction components
        }
        directions[i] = glm::vec4(glm::normalize(d), 0.0f);
    }
    const std::vector<glm::vec4> hits = traceRays(gpuScene, origins, directions);
    EXPECT_GT(expectBruteForceHits(scene, bvh, origins, directions, hits), int(kRays / 4));

    // The same rays leaving the triangle they hit first find the next one behind it.
    for (uint32_t i = 0; i < kRays; ++i) {
        origins[i].w = hits[i].w;
    }
    const std::vector<glm::vec4> behind = traceRays(gpuScene, origins, directions);
    EXPECT_GT(expectBruteForceHits(scene, bvh, origins, directions, behind), int(kRays / 8));
}

}  // namespace
}  // namespace vkdr::test
