#include "cli/sampling_options.h"

#include <charconv>
#include <limits>

#include "scene/parameter_kinds.h"

namespace vkdr {

CLI::Validator integerIn(uint64_t low, uint64_t high, const std::string& kind) {
    const std::string expected =
        kind.empty() ? "an integer from " + std::to_string(low) + " to " + std::to_string(high) : kind;
    return CLI::Validator(
        [=](std::string& input) -> std::string {
            uint64_t value = 0;
            const char* end = input.data() + input.size();
            auto [stop, ec] = std::from_chars(input.data(), end, value);
            bool digitsOnly = !input.empty() && input.find_first_not_of("0123456789") == std::string::npos;
            if (!digitsOnly || ec != std::errc() || stop != end || value < low || value > high) {
                return "must be " + expected + ", got " + input;
            }
            input = std::to_string(value);
            return "";
        },
        "UINT in [" + std::to_string(low) + " - " + std::to_string(high) + "]");
}

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
    command.add_option("--paths-per-pass", settings.pathsPerPass,
                       "Paths in flight per pass (default: up to 2^21 on a GPU, 2^20 on a CPU, as device memory allows)")
        ->transform(integerIn(1, 1u << 21));
    return options;
}

}  // namespace vkdr
