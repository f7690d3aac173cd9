#include "vk/specialized_spirv.h"

#include <spirv-tools/optimizer.hpp>

#include <stdexcept>
#include <unordered_map>

namespace vkdr {

std::vector<uint32_t> specializedSpirv(const std::string& name, std::span<const uint32_t> spirv,
                                       std::span<const uint32_t> constants) {
    std::unordered_map<uint32_t, std::vector<uint32_t>> values;
    for (uint32_t id = 0; id < constants.size(); ++id) {
        values[id] = {constants[id]};
    }
    std::string messages;
    spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_2);
    optimizer.SetMessageConsumer([&messages](spv_message_level_t, const char*, const spv_position_t&,
                                             const char* message) { messages += std::string(message) + "; "; });
    // Fix the constants, fold what they decide, then drop the branches and functions
    // that became unreachable and the code left without a use.
    optimizer.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(values))
        .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateCCPPass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass());
    // The modules are the build's own glslang output, and the tests create every
    // pipeline under the validation layer, which validates the result: validating the
    // input again would take a third of the optimiser's time.
    spvtools::OptimizerOptions options;
    options.set_run_validator(false);
    std::vector<uint32_t> specialized;
    if (!optimizer.Run(spirv.data(), spirv.size(), &specialized, options)) {
        throw std::logic_error("specializing shader " + name + " failed: " + messages);
    }
    return specialized;
}

}  // namespace vkdr
