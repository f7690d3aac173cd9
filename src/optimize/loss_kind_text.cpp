#include "optimize/loss_kind_text.h"

#include "core/error.h"

namespace vkdr {

LossKind parseLossKind(std::string_view text) {
    if (text == "l2") return LossKind::L2;
    if (text == "l1") return LossKind::L1;
    throw Error("unknown loss '" + std::string(text) + "'; expected l2 or l1");
}

std::string lossKindName(LossKind kind) { return kind == LossKind::L2 ? "l2" : "l1"; }

}  // namespace vkdr
