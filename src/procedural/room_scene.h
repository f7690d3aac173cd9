#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>

namespace vkdr {

struct Fog {
    float sigma_a = 0.0f;  // per scene unit, all channels
    float sigma_s = 0.0f;
};

struct RoomSceneOptions {
    uint64_t triangles = 100000;  // approximate total
    std::filesystem::path output;
    std::optional<Fog> fog;       // the scene-wide medium "fog", when set
    // Every length times this (the meshes by their node's scale, the camera by its
    // position): in vacuum the image is the same, in a fog the optical depths grow.
    float scale = 1.0f;
};

// A closed 10 x 5 x 10 room, times `scale` (white walls, an area light in the ceiling, a
// camera looking in) holding a grid of bumpy spheres, written as a .glb. Returns the
// exact triangle count.
uint64_t writeRoomScene(const RoomSceneOptions& options);

}  // namespace vkdr
