#pragma once
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace vkdr {

// Checks for floating-point options. CLI11's PositiveNumber and Range only compare, and
// NaN fails no comparison, so they let "nan" through; these also refuse NaN and
// infinities (and "1e999", which reads as infinity).

// A finite number > 0.
CLI::Validator finitePositiveNumber();

// A finite number in [lower, upper].
CLI::Validator finiteNumberIn(double lower, double upper);

// A transform (Option::transform; check() would not pass its result on) that accepts
// decimal digits naming an integer in [low, high] and passes it on in canonical form
// (CLI11 would read "010" as octal 8 and "0x10" as 16); anything else is refused
// saying what is expected: "must be an integer from 1 to 16384, got 1.5". `kind`
// replaces "an integer from low to high" where a name says more (the seed's).
CLI::Validator integerIn(uint64_t low, uint64_t high, const std::string& kind = "");

// Refuses an empty value ("--png ''"), saying what to give ("give a file name"): for an
// option whose absence means "none" or "the default", an empty value would silently mean
// that too.
CLI::Validator nonEmpty(const std::string& what);


}  // namespace vkdr
