#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkdr {

// A scene to benchmark, by the name given on the command line:
// - a shipped scene: "cornell_fog" reads <scenes directory>/cornell_fog.gltf;
// - a procedural room: "room_<N>" with N triangles, "k" and "m" suffixes allowed
//   ("room_10k", "room_1m"): the vkdr-make-scene generator's room of spheres with the
//   scene-wide medium "fog";
// - a path to a .gltf or .glb file.
struct BenchSceneSource {
    std::string name;
    std::filesystem::path file;  // empty for a procedural room
    uint64_t roomTriangles = 0;  // the room's triangle budget
};

// cornell_fog, cornell_smoke, and rooms of 10k, 100k, 1M and 10M triangles.
std::vector<std::string> defaultBenchScenes();

// Throws vkdr::Error naming `name` when it is none of the above.
BenchSceneSource resolveBenchScene(const std::string& name, const std::filesystem::path& scenesDirectory);

// Why a procedural room would not fit in memory, from its triangle count and the bytes
// per triangle measured at 1M triangles; nothing when it fits (or for other scenes,
// whose size is known only once loaded). On a CPU device the device memory is host
// memory too, so both shares count against the host.
std::optional<std::string> whyTooLarge(const BenchSceneSource& source, uint64_t availableHostBytes,
                                       uint64_t deviceHeapBytes, bool deviceIsHost);

// Loads (or generates) the scene; the room's .glb goes through a temporary file.
Scene loadBenchScene(const BenchSceneSource& source);

}  // namespace vkdr
