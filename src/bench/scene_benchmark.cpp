#include "bench/scene_benchmark.h"

#include <algorithm>
#include <tuple>
#include <utility>
#include <vector>

#include "bench/efficiency.h"
#include "bench/host_memory.h"
#include "bench/image_noise.h"
#include "bench/median.h"
#include "bvh/bvh.h"
#include "core/milliseconds_of.h"
#include "render/renderer.h"
#include "scene/parameter_kinds.h"
#include "vk/context.h"
#include "vk/dispatch_timer.h"

namespace vkdr {
namespace {

// The target is rendered with one seed, forward passes and gradient iterations with
// another; forward passes alternate with a third, for the noise of a render.
constexpr uint32_t kTargetSeed = 1;
constexpr uint32_t kImageSeed = 2;
constexpr uint32_t kSecondImageSeed = 3;

double sum(const std::map<std::string, double>& times) {
    double total = 0.0;
    for (const auto& [name, ms] : times) {
        total += ms;
    }
    return total;
}

// One gradient iteration's stage times, keyed as in SceneBenchmark.
struct StageTimes {
    std::map<std::string, double> stages, adjointStages;
};

StageTimes stageTimes(const DispatchTimer::Milliseconds& timed) {
    StageTimes out;
    auto scope = [&](const char* name) -> const std::map<std::string, double>& {
        static const std::map<std::string, double> none;
        auto it = timed.find(name);
        return it == timed.end() ? none : it->second;
    };
    for (const auto& [pipeline, ms] : scope("forward")) {
        out.stages[pipeline] += ms;
    }
    for (const auto& [pipeline, ms] : scope("adjoint")) {
        out.adjointStages[pipeline] += ms;
    }
    out.stages["loss"] = sum(scope("loss"));
    out.stages["replay"] = sum(scope("replay"));
    out.stages["adjoint"] = sum(scope("adjoint"));
    out.stages["gradient_values"] = sum(scope("gradient_values"));
    return out;
}

std::map<std::string, double> medians(const std::vector<std::map<std::string, double>>& samples) {
    std::map<std::string, std::vector<double>> byKey;
    for (const auto& sample : samples) {
        for (const auto& [key, value] : sample) {
            byKey[key].push_back(value);
        }
    }
    std::map<std::string, double> out;
    for (auto& [key, values] : byKey) {
        values.resize(samples.size(), 0.0);  // a stage that did not run in an iteration took 0
        out[key] = median(values);
    }
    return out;
}

class Progress {
public:
    Progress(const std::function<void(double)>& report, uint32_t steps) : report_(report), total_(double(steps)) {}
    void step() {
        if (report_) {
            report_(++done_ / total_);
        }
    }

private:
    const std::function<void(double)>& report_;
    double total_;
    double done_ = 0.0;
};

// The median wall-clock time of `iterations` runs of `run(i)`, with a progress step
// after each.
template <typename Run>
double medianMillisecondsOf(uint32_t iterations, Progress& steps, Run&& run) {
    std::vector<double> ms;
    for (uint32_t i = 0; i < iterations; ++i) {
        ms.push_back(millisecondsOf([&] { run(i); }));
        steps.step();
    }
    return median(ms);
}

// The median wall-clock times of `iterations` runs each of `first(i)` and `second()`,
// taken in turn, so that a machine that slows down or speeds up during the measurement
// changes both alike and their ratio holds; a progress step after each run.
template <typename First, typename Second>
std::pair<double, double> medianMillisecondsInTurn(uint32_t iterations, Progress& steps, First&& first,
                                                   Second&& second) {
    std::vector<double> firstMs, secondMs;
    for (uint32_t i = 0; i < iterations; ++i) {
        firstMs.push_back(millisecondsOf([&] { first(i); }));
        steps.step();
        secondMs.push_back(millisecondsOf([&] { second(); }));
        steps.step();
    }
    return {median(firstMs), median(secondMs)};
}

bool hasDensityGridMedium(const Scene& scene) {
    return std::any_of(scene.media.begin(), scene.media.end(), [](const Medium& m) { return m.isHeterogeneous(); });
}

// The forward, gradient, stage and memory figures of `result`, from one renderer, and
// then, for a scene with a density grid, gradient iterations of its density alone (the
// memory figures are those of every parameter's gradient); returns the target image its
// gradient iterations used.
Image measureRenderer(const VulkanContext& context, const Scene& scene, const Bvh& bvh, const BenchSettings& settings,
                      uint32_t iterations, Progress& steps, SceneBenchmark& result) {
    context.allocations().resetPeak();
    std::optional<uint64_t> driverPeak;
    auto sampleDriverMemory = [&] {
        if (std::optional<uint64_t> used = context.deviceLocalHeapUsage()) {
            driverPeak = std::max(driverPeak.value_or(0), *used);
        }
    };
    RenderSettings renderSettings = settings.render;
    renderSettings.seed = kTargetSeed;
    Renderer renderer(context, scene, bvh, renderSettings);
    result.width = renderer.width();
    result.height = renderer.height();
    Image target = renderer.render();
    renderer.enableGradients(target, LossKind::L2);
    renderer.setSeed(kImageSeed);
    steps.step();

    auto gradientIteration = [&] { renderer.renderWithGradients(); };
    gradientIteration();  // warm-up: compiles the adjoint pipelines
    sampleDriverMemory();
    steps.step();

    auto forwardPass = [&](uint32_t i) {
        renderer.setSeed(i % 2 == 0 ? kImageSeed : kSecondImageSeed);
        return renderer.render();
    };
    Image images[2];
    auto forwardPassCounted = [&](uint32_t i) {
        images[i % 2] = forwardPass(i);
        result.paths = renderer.stats().paths;
        result.rays = renderer.stats().rays;
    };
    auto gradientIterationAtImageSeed = [&] {
        renderer.setSeed(kImageSeed);
        gradientIteration();
    };
    std::tie(result.forwardMs, result.gradientMs) =
        medianMillisecondsInTurn(iterations, steps, forwardPassCounted, gradientIterationAtImageSeed);
    result.relativeNoise = relativeNoise(images[0], images[1]);

    // The driver's memory figure is sampled in these iterations, outside the wall-clock
    // medians above.
    DispatchTimer timer(context);
    renderer.setDispatchTimer(&timer);
    std::vector<std::map<std::string, double>> stages, adjointStages;
    for (uint32_t i = 0; i < iterations; ++i) {
        timer.clear();
        gradientIteration();
        sampleDriverMemory();
        StageTimes times = stageTimes(timer.milliseconds());
        stages.push_back(times.stages);
        adjointStages.push_back(times.adjointStages);
        steps.step();
    }
    renderer.setDispatchTimer(nullptr);
    result.stagesMs = medians(stages);
    result.adjointStagesMs = medians(adjointStages);

    result.peakAllocatedDeviceBytes = context.allocations().peak();
    result.peakDriverDeviceBytes = driverPeak;
    result.peakHostBytes = peakHostResidentBytes();

    if (hasDensityGridMedium(scene)) {
        renderer.enableGradients(target, LossKind::L2, DerivativeTargets::of({ParameterKind::Density}));
        gradientIteration();  // warm-up: compiles the density-only adjoint pipelines
        DensityGradientTimes density;
        std::tie(density.forwardMs, density.gradientMs) =
            medianMillisecondsInTurn(iterations, steps, forwardPass, gradientIterationAtImageSeed);
        result.densityGradient = density;
    }
    return target;
}

}  // namespace

std::optional<double> SceneBenchmark::efficiency() const {
    return relativeNoise ? efficiencyOf(*relativeNoise, forwardMs * 1e-3) : std::nullopt;
}

SceneBenchmark benchmarkScene(const VulkanContext& context, const std::string& name, const Scene& scene,
                              const BenchSettings& settings, const std::function<void(double)>& progress) {
    const uint32_t iterations = std::max(1u, settings.iterations);
    const uint32_t gradientSeeds = benchGradientParameter(scene) ? settings.gradientSeeds : 0;
    const uint32_t densitySteps = hasDensityGridMedium(scene) ? 2 * iterations : 0;
    Progress steps(progress, 4 * iterations + 3 + densitySteps + gradientSeeds);
    SceneBenchmark result;
    result.name = name;
    result.triangles = scene.triangles.size();
    result.spp = settings.render.spp;
    result.maxDepth = settings.render.maxDepth;

    Bvh bvh = buildBvh(scene.positions, scene.triangles);  // warm-up: starts the thread pool
    steps.step();
    result.bvhBuildMs = medianMillisecondsOf(iterations, steps,
                                             [&](uint32_t) { bvh = buildBvh(scene.positions, scene.triangles); });
    result.densityGrids = measureDensityGrids(scene, iterations);

    const Image target = measureRenderer(context, scene, bvh, settings, iterations, steps, result);
    result.gradient =
        benchmarkGradient(context, scene, bvh, target, settings.render, gradientSeeds, [&] { steps.step(); });
    return result;
}

}  // namespace vkdr
