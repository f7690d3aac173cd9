#pragma once

namespace vkdr {

enum class LossKind {
    L2,  // mean over pixels and colour channels of (I - T)^2
    L1,  // mean over pixels and colour channels of |I - T|
};

}  // namespace vkdr
