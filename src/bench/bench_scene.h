#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/load_scene.h"
#include "scene/scene.h"

namespace vkdr {

// A scene to benchmark, by the name given on the command line:
// - a shipped scene: "cornell_fog" reads <scenes directory>/cornell_fog.gltf;
// - a procedural room: "room_<N>" with N triangles, "k" and "m" suffixes allowed
//   ("room_10k", "room_1m"): the vkdr-make-scene generator's room of spheres with the
//   scene-wide medium "fog";
// - a procedural plume: "plume_<N>" is the shipped cornell_plume.gltf with its density
//   grid replaced by makeSmokePlume(N, seed 1), placed in the same box (plume_64 has the
//   shipped grid's voxels);
// - a path to a .gltf or .glb file.
struct BenchSceneSource {
    std::string name;
    std::filesystem::path file;  // empty for a procedural room; cornell_plume.gltf for a plume
    uint64_t roomTriangles = 0;  // the room's triangle budget
    int plumeResolution = 0;     // the plume's voxels along each axis; 0: the scene's own grids
};

// cornell_fog, cornell_smoke, the 64^3 plume, and rooms of 10k, 100k, 1M and 10M triangles.
std::vector<std::string> defaultBenchScenes();

// Throws vkdr::Error naming `name` when it is none of the above.
BenchSceneSource resolveBenchScene(const std::string& name, const std::filesystem::path& scenesDirectory);

// The most memory a procedural room or plume takes while it is generated, loaded, built
// and rendered, from its triangle or voxel count; 0 for other scenes.
struct BenchMemoryEstimate {
    uint64_t hostBytes = 0;    // besides the device's
    uint64_t deviceBytes = 0;  // our buffers, staging buffers included
    // The device heap that runs it: deviceBytes, and at least twice the density
    // gradient's fixed-point sums, since the renderer allows those half the heap.
    uint64_t deviceHeapBytes = 0;
};
BenchMemoryEstimate estimateBenchMemory(const BenchSceneSource& source);

// Why a procedural room or plume would not fit in memory, from its triangle count and
// the bytes per triangle measured at 1M triangles, or its voxel count and the bytes per
// voxel measured on plumes; nothing when it fits (or for other scenes, whose size is
// known only once loaded). On a CPU device the device memory is host memory too, so
// both shares count against the host.
std::optional<std::string> whyTooLarge(const BenchSceneSource& source, uint64_t availableHostBytes,
                                       uint64_t deviceHeapBytes, bool deviceIsHost);

// Loads (or generates) the scene; the room's .glb goes through a temporary file, the
// plume stays in memory. The files read besides the scene's own are those of a glTF
// source (LoadedScene::externalFiles); none for a generated one.
LoadedScene loadBenchScene(const BenchSceneSource& source, const SceneFileAccess& access = {});

}  // namespace vkdr
