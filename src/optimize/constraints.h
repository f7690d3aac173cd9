#pragma once
#include <span>
#include <string_view>

#include "scene/parameter_kinds.h"

namespace vkdr {

// The closed interval a parameter's values are kept in while optimising: its kind's
// range (scene/parameter_kinds.h), the same that setting a value enforces. Throws
// vkdr::Error for a name that fits no kind's pattern.
ValueRange boundsForParameter(std::string_view name);

// Euclidean projection onto the bounds: each value clamped.
void projectOntoBounds(std::span<double> values, const ValueRange& bounds);

}  // namespace vkdr
