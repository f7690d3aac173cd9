#pragma once
#include <string>
#include <string_view>

#include "diff/loss_gradient.h"

namespace vkdr {

// "l2" or "l1", as the command line and experiment files spell them; anything else is
// a vkdr::Error listing both.
LossKind parseLossKind(std::string_view text);
std::string lossKindName(LossKind kind);

}  // namespace vkdr
