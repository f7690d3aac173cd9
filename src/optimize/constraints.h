#pragma once
#include <span>
#include <string_view>

namespace vkdr {

// The closed interval a parameter's values are kept in while optimising.
struct ValueBounds {
    double lower;
    double upper;
};

// Short of the loader's |g| < 1: a phase function this peaked is already a delta for
// any image we can render, and the g gradient's 1/(1-g^2) term blows up beyond it.
inline constexpr double kMaxAbsAnisotropy = 0.99;

// Decided by the name's last component: sigma_a and sigma_s >= 0, |g| <= 0.99,
// base_color in [0, 1], emission >= 0. Throws vkdr::Error for any other.
ValueBounds boundsForParameter(std::string_view name);

// Euclidean projection onto the bounds: each value clamped.
void projectOntoBounds(std::span<double> values, const ValueBounds& bounds);

}  // namespace vkdr
