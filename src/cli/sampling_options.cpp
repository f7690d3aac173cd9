#include "cli/sampling_options.h"

#include <limits>

#include "cli/number_options.h"
#include "scene/parameter_kinds.h"

namespace vkdr {

SamplingOptions addSamplingOptions(CLI::App& command, RenderSettings& settings) {
    SamplingOptions options;
    options.spp = command.add_option("--spp", settings.spp, "Samples per pixel")
                      ->default_val(settings.spp)
                      ->transform(integerIn(1, kMaxSamplesPerPixel));
    options.maxDepth =
        command
            .add_option("--max-depth", settings.maxDepth,
                        "Scattering vertices per path (surface bounces + medium scattering); 1 = direct light only")
            ->default_val(settings.maxDepth)
            ->transform(integerIn(0, kMaxScatteringVertices));
    constexpr uint64_t kMaxSeed = std::numeric_limits<uint32_t>::max();
    options.seed = command.add_option("--seed", settings.seed, "Random seed; the same seed gives the same image")
                       ->default_val(settings.seed)
                       ->transform(integerIn(0, kMaxSeed, "a 32-bit unsigned integer (0.." + std::to_string(kMaxSeed) + ")"));
    command.add_flag_callback("--no-equiangular", [&settings] { settings.equiangularSampling = false; },
                              "Estimate direct light in homogeneous media from distance-sampled collisions "
                              "only, without equiangular sampling towards the lights: faster, noisier near lights");
    command.add_option("--paths-per-pass", settings.pathsPerPass,
                       "Paths in flight per pass (default: up to 2^21 on a GPU, 2^20 on a CPU, as device memory allows)")
        ->transform(integerIn(1, 1u << 21));
    return options;
}

}  // namespace vkdr
