#include "cli/sampling_options.h"

namespace vkdr {

SamplingOptions addSamplingOptions(CLI::App& command, RenderSettings& settings) {
    SamplingOptions options;
    options.spp = command.add_option("--spp", settings.spp, "Samples per pixel")
                      ->default_val(settings.spp)
                      ->check(CLI::Range(1u, kMaxSamplesPerPixel));
    options.maxDepth =
        command
            .add_option("--max-depth", settings.maxDepth,
                        "Scattering vertices per path (surface bounces + medium scattering); 1 = direct light only")
            ->default_val(settings.maxDepth)
            ->check(CLI::Range(0u, 100000u));
    options.seed = command.add_option("--seed", settings.seed, "Random seed; the same seed gives the same image")
                       ->default_val(settings.seed);
    command.add_option("--paths-per-pass", settings.pathsPerPass,
                       "Paths in flight per pass (default: up to 2^21 on a GPU, 2^20 on a CPU, as device memory allows)")
        ->check(CLI::Range(1u, 1u << 21));
    return options;
}

}  // namespace vkdr
