#pragma once
#include <cstddef>
#include <span>

#include "device_types.h"

namespace vkdr {

// Mirrors the push-constant block of shaders/lib/stage_common.glsl.
struct PushConstants {
    uint64_t params;  // device address of the RenderParams
    gpu::PassConstants pass;

    std::span<const std::byte> bytes() const { return std::as_bytes(std::span(this, 1)); }
};
static_assert(offsetof(PushConstants, pass) == 8);
static_assert(sizeof(PushConstants) == 40);

}  // namespace vkdr
