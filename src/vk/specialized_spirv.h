#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vkdr {

// `spirv` with its specialization constants fixed to `constants` (constants[i] is the
// value of constant_id i; for a bool, 0 is false) and the code they switch off removed,
// as a driver would after specialization. lavapipe inlines and lowers every function a
// shader calls before it folds the constants, so a stage's code for scene features the
// scene lacks would otherwise cost it most of a pipeline's creation time.
std::vector<uint32_t> specializedSpirv(const std::string& name, std::span<const uint32_t> spirv,
                                       std::span<const uint32_t> constants);

}  // namespace vkdr
