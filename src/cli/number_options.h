#pragma once
#include <CLI/CLI.hpp>

namespace vkdr {

// Checks for floating-point options. CLI11's PositiveNumber and Range only compare, and
// NaN fails no comparison, so they let "nan" through; these also refuse NaN and
// infinities (and "1e999", which reads as infinity).

// A finite number > 0.
CLI::Validator finitePositiveNumber();

// A finite number in [lower, upper].
CLI::Validator finiteNumberIn(double lower, double upper);

}  // namespace vkdr
