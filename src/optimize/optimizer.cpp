#include "optimize/optimizer.h"

#include <cmath>

#include "core/error.h"
#include "optimize/adam.h"
#include "optimize/sgd.h"

namespace vkdr {

OptimizerKind parseOptimizerKind(std::string_view text) {
    if (text == "adam") return OptimizerKind::Adam;
    if (text == "sgd") return OptimizerKind::Sgd;
    throw Error("unknown optimizer '" + std::string(text) + "'; expected adam or sgd");
}

std::string optimizerKindName(OptimizerKind kind) { return kind == OptimizerKind::Adam ? "adam" : "sgd"; }

std::unique_ptr<Optimizer> makeOptimizer(OptimizerKind kind, std::vector<double> learningRates,
                                         double adamEpsilon) {
    for (double rate : learningRates) {
        if (!(rate > 0.0) || !std::isfinite(rate)) {
            throw Error("a learning rate must be finite and > 0, got " + std::to_string(rate));
        }
    }
    if (!(adamEpsilon > 0.0) || !std::isfinite(adamEpsilon)) {
        throw Error("Adam's epsilon must be finite and > 0, got " + std::to_string(adamEpsilon));
    }
    if (kind == OptimizerKind::Adam) {
        return std::make_unique<AdamOptimizer>(std::move(learningRates), AdamMoments{.epsilon = adamEpsilon});
    }
    return std::make_unique<SgdOptimizer>(std::move(learningRates));
}

}  // namespace vkdr
