#pragma once
#include <CLI/CLI.hpp>

#include "render/render_settings.h"

namespace vkdr {

// The options that set how a render samples, shared by every command that renders.
struct SamplingOptions {
    CLI::Option* spp;
    CLI::Option* maxDepth;
    CLI::Option* seed;
};

// --spp, --max-depth, --seed, --no-equiangular and --paths-per-pass, with their ranges in
// one place.
SamplingOptions addSamplingOptions(CLI::App& command, RenderSettings& settings);

}  // namespace vkdr
