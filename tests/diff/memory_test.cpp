// Path replay keeps memory constant in the path depth: the adjoint pass stores nothing
// per vertex, so rendering and differentiating at max depth 4 and 64 reach the same peak
// of device memory, as the context's allocation counter (every Buffer reports to it)
// measures it.
//
// Why this can fail: any buffer sized by the depth, kept per vertex or allocated while a
// path goes deeper, is a Buffer counted here, and at depth 64 its size would be 16 times
// larger or more, so the peak would grow by at least (64 - 4) vertices times the bytes per
// vertex. The furnace makes paths go that deep: its walls reflect 90 %, so at depth 64 the
// image is clearly brighter than at depth 4, which the test checks against the image's
// standard error before it compares the peaks.
#include <cmath>

#include "bvh/bvh.h"
#include "furnace_scene.h"
#include "render/renderer.h"
#include "render_test_support.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

class MemoryTest : public RenderTest {};

struct DepthRun {
    uint64_t peakDeviceBytes;
    PixelStatistics image;
};

TEST_F(MemoryTest, DepthDoesNotChangePeakDeviceMemory) {
    Scene scene = loadScene(furnace(glm::vec3(0.9f)).write(tempDir(), "furnace")).scene;
    Bvh bvh = buildBvh(scene.positions, scene.triangles);
    Image target{16, 16, std::vector<float>(16 * 16 * 3, 0.1f)};
    AllocationCounter& allocations = testContext().allocations();
    auto run = [&](uint32_t maxDepth) {
        allocations.resetPeak();
        Renderer renderer(testContext(), scene, bvh, {.width = 16, .height = 16, .spp = 4, .maxDepth = maxDepth});
        Image image = renderer.render();
        renderer.enableGradients(target, LossKind::L2);
        renderer.renderWithGradients();
        return DepthRun{allocations.peak(), pixelStatistics(image)};
    };
    // The context keeps its staging buffers from one transfer to the next: a first run
    // makes them, so that both measured runs start with the same memory held.
    run(4);
    const DepthRun shallow = run(4);
    const DepthRun deep = run(64);
    for (int c = 0; c < 3; ++c) {
        const double error = std::hypot(shallow.image.standardError[c], deep.image.standardError[c]);
        EXPECT_GT(deep.image.mean[c] - shallow.image.mean[c], 5.0 * error) << "paths do not go past depth 4";
    }
    EXPECT_GT(shallow.peakDeviceBytes, 0u);
    EXPECT_EQ(shallow.peakDeviceBytes, deep.peakDeviceBytes);
}

}  // namespace
}  // namespace vkdr::test
