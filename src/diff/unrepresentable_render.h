#pragma once
#include <optional>
#include <string>

#include "diff/loss_gradient.h"

namespace vkdr {

// The first pixel of a gradient evaluation's renders that no loss can take (NaN,
// infinite, or beyond kMaxPixelMagnitude), as "the render of view 1: pixel (3, 4) channel R
// is +infinity"; nullopt when there is none. A loss or gradient that is not finite while
// such a pixel exists comes from the scene's values, which make more light than a float
// holds, rather than from the loss or the steps.
std::optional<std::string> unrepresentableRender(const GradientResult& result);

}  // namespace vkdr
