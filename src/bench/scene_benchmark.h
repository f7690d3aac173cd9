#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "bench/density_grid_figures.h"
#include "bench/gradient_benchmark.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace vkdr {

class VulkanContext;

struct BenchSettings {
    RenderSettings render;    // size, spp and max depth; the seed is the benchmark's own
    uint32_t iterations = 3;  // timed repetitions of each measurement, after one warm-up
    // Seeds of the gradient noise measurement (bench/gradient_benchmark.h); 0 skips it.
    // Eight give its standard deviation to about 1 / sqrt(2 x 7) = 27 %.
    uint32_t gradientSeeds = 8;
};

// Wall-clock medians of gradient iterations of the density alone and of the forward
// passes timed in turn with them.
struct DensityGradientTimes {
    double forwardMs = 0.0;
    double gradientMs = 0.0;
};

// What one scene costs: medians over the timed iterations.
struct SceneBenchmark {
    std::string name;
    uint64_t triangles = 0;
    int width = 0, height = 0;
    uint32_t spp = 0, maxDepth = 0;
    double bvhBuildMs = 0.0;
    std::optional<DensityGridFigures> densityGrids;  // nullopt for a scene without grids
    double forwardMs = 0.0;   // Renderer::render(), wall clock
    double gradientMs = 0.0;  // Renderer::renderWithGradients(), wall clock
    // Gradient iterations with the adjoint set up for the density grids' voxels alone, as
    // a grid fit runs it (the other kinds' additions compiled out), and the forward
    // passes timed in turn with them; nullopt without a density grid.
    std::optional<DensityGradientTimes> densityGradient;
    uint64_t paths = 0;       // of one forward pass
    uint64_t rays = 0;        // closest-hit and shadow rays of one forward pass
    // The forward passes' per-pixel relative noise (bench/image_noise.h), from the last
    // two, which differ only in the seed; nullopt for a black image.
    std::optional<double> relativeNoise;
    // GPU milliseconds by stage (DispatchTimer) in a gradient iteration: its rendering
    // passes' generate, intersect, medium_sample, shade, shadow, queue_prepare and film;
    // then loss; replay, primal passes rendered again for the adjoint (none when the
    // samples split, Renderer::renderWithGradients); adjoint, its adjoint-mode passes.
    std::map<std::string, double> stagesMs;
    std::map<std::string, double> adjointStagesMs;  // "adjoint" by stage
    uint64_t peakAllocatedDeviceBytes = 0;          // the most held at once by our buffers
    std::optional<uint64_t> peakDriverDeviceBytes;  // device-local heap use, VK_EXT_memory_budget
    uint64_t peakHostBytes = 0;                     // peak resident set since the caller's reset
    // A medium parameter's gradient over seeds, its noise and cost; nullopt for a scene
    // without one (benchGradientParameter) or with 0 gradient seeds.
    std::optional<GradientBenchmark> gradient;

    double trianglesPerSecond() const { return bvhBuildMs > 0.0 ? double(triangles) / (bvhBuildMs * 1e-3) : 0.0; }
    double pathsPerSecond() const { return forwardMs > 0.0 ? double(paths) / (forwardMs * 1e-3) : 0.0; }
    double raysPerSecond() const { return forwardMs > 0.0 ? double(rays) / (forwardMs * 1e-3) : 0.0; }
    double gradientToForward() const { return forwardMs > 0.0 ? gradientMs / forwardMs : 0.0; }
    std::optional<double> densityGradientToForward() const {
        return densityGradient && densityGradient->forwardMs > 0.0
                   ? std::optional(densityGradient->gradientMs / densityGradient->forwardMs)
                   : std::nullopt;
    }
    // 1 / (noise^2 x forward seconds); none without a noise figure, or with a noise of 0.
    std::optional<double> efficiency() const;
};

// Times the BVH build, counts the density grids' voxels and times their majorant grids'
// build, then renders: a warm-up render that becomes the target image, one warm-up
// gradient iteration, and then `iterations` (at least 2) each of forward passes
// (alternating between two seeds, for the noise figure) in turn with gradient iterations
// (as RenderedLossGradient runs them), and gradient iterations with a DispatchTimer
// attached for the stage times, so that the timestamps do not slow the wall-clock
// figures. The memory figures end there; a scene with a density grid then times
// `iterations` gradient iterations of the density alone in turn with forward passes.
// With that renderer gone, benchmarkGradient measures the gradient noise against the
// same target.
// `progress` gets the fraction done.
SceneBenchmark benchmarkScene(const VulkanContext& context, const std::string& name, const Scene& scene,
                              const BenchSettings& settings, const std::function<void(double)>& progress);

}  // namespace vkdr
