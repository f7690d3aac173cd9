#pragma once
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "render/render_settings.h"

namespace vkdr {

// The options that set how a render samples, shared by every command that renders.
struct SamplingOptions {
    CLI::Option* spp;
    CLI::Option* maxDepth;
    CLI::Option* seed;
};

// --spp, --max-depth, --seed and --paths-per-pass, with their ranges in one place.
SamplingOptions addSamplingOptions(CLI::App& command, RenderSettings& settings);

// A transform (Option::transform; check() would not pass its result on) that accepts
// decimal digits naming an integer in [low, high] and passes it on in canonical form
// (CLI11 would read "010" as octal 8 and "0x10" as 16); anything else is refused
// saying what is expected: "must be an integer from 1 to 16384, got 1.5". `kind`
// replaces "an integer from low to high" where a name says more (the seed's).
CLI::Validator integerIn(uint64_t low, uint64_t high, const std::string& kind = "");

}  // namespace vkdr
