#include "bench/bench_scene.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <optional>
#include <system_error>

#include "core/error.h"
#include "core/format_text.h"
#include "device_types.h"
#include "image/regular_file.h"
#include "procedural/room_scene.h"
#include "scene/load_scene.h"
#include "volume/index_transform.h"
#include "volume/smoke_plume.h"

namespace vkdr {
namespace {

constexpr const char* kRoomPrefix = "room_";
// Thin enough that most paths reach a surface, thick enough that every medium stage works.
constexpr Fog kRoomFog{0.01f, 0.05f};
constexpr uint64_t kMaxRoomTriangles = uint64_t(1) << 30;
// Peaks per triangle while a room is generated, loaded, built and rendered, with about
// a third as margin over what bench measures on room_1m (docs/performance.md).
constexpr uint64_t kHostBytesPerTriangle = 500;
constexpr uint64_t kDeviceBytesPerTriangle = 200;

constexpr const char* kPlumePrefix = "plume_";
constexpr const char* kPlumeScene = "cornell_plume";
constexpr uint32_t kPlumeSeed = 1;  // the shipped grid's
// Peaks per voxel of a plume, with about a third as margin over what bench measures
// (plume_64 to plume_192, docs/performance.md). On the device 8.5 bytes while the grid
// is uploaded (its values and their staging copy), and 84 once the density gradient is
// read: the values, the gradient's fixed-point sums (72 bytes), their floats and the
// floats' staging copy (4 each). On the host 9 to 17 besides: the scene's values and the
// gradient's floats.
constexpr uint64_t kHostBytesPerVoxel = 24;
constexpr uint64_t kForwardDeviceBytesPerVoxel = 12;
constexpr uint64_t kGradientDeviceBytesPerVoxel = 108;

// "10k" -> 10000, "1m" -> 1000000; nothing for anything else or too large to multiply.
std::optional<uint64_t> parseCount(const std::string& text) {
    uint64_t value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end == text.data()) {
        return std::nullopt;
    }
    std::string suffix(end, text.data() + text.size());
    uint64_t scale = suffix == "k" ? 1000 : suffix == "m" ? 1000000 : 1;
    if ((scale == 1 && !suffix.empty()) || value > kMaxRoomTriangles) {
        return std::nullopt;
    }
    return value * scale;
}

// "64" -> 64; nothing unless the whole text is a resolution makeSmokePlume takes.
std::optional<int> parseResolution(const std::string& text) {
    int value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < 2 ||
        uint64_t(value) * uint64_t(value) * uint64_t(value) > kMaxDenseVoxels) {
        return std::nullopt;
    }
    return value;
}

// Puts a procedural plume of resolution^3 voxels in place of each medium's density grid,
// keeping the node's placement: the plume fills the box the old grid filled.
void replaceGridsWithPlume(Scene& scene, const BenchSceneSource& source) {
    std::vector<size_t> densities;
    for (const Medium& medium : scene.media) {
        if (medium.isHeterogeneous()) densities.push_back(size_t(medium.densityGrid));
    }
    if (densities.empty()) {
        throw Error("scene " + source.name + ": " + source.file.string() + " has no density grid to replace");
    }
    for (size_t index : densities) {
        SceneDensityGrid& placed = scene.densityGrids[index];
        DensityGrid plume = makeSmokePlume(source.plumeResolution, kPlumeSeed);
        plume.name = placed.grid.name;
        const glm::dmat4 nodeToWorld = placed.indexToWorld * glm::inverse(placed.grid.indexToLocal);
        placed.indexToWorld = nodeToWorld * plume.indexToLocal;
        placed.grid = std::move(plume);
        placed.file = source.name;  // errors about the grid name the bench scene
    }
}

bool looksLikeFile(const std::string& name) {
    std::filesystem::path path(name);
    return path.has_parent_path() || path.extension() == ".gltf" || path.extension() == ".glb";
}

}  // namespace

std::vector<std::string> defaultBenchScenes() {
    return {"cornell_fog", "cornell_smoke", "plume_64", "room_10k", "room_100k", "room_1m", "room_10m"};
}

BenchSceneSource resolveBenchScene(const std::string& name, const std::filesystem::path& scenesDirectory) {
    if (looksLikeFile(name)) {
        if (const std::string reason = notRegularFileReason(name); !reason.empty()) {
            throw Error("scene " + name + ": " + reason);
        }
        return {name, name};
    }
    if (name.starts_with(kRoomPrefix)) {
        std::optional<uint64_t> triangles = parseCount(name.substr(std::string(kRoomPrefix).size()));
        if (!triangles || *triangles == 0 || *triangles > kMaxRoomTriangles) {
            throw Error("scene " + name + ": expected room_<N> with N from 1 to 2^30 triangles, e.g. room_100k");
        }
        return {name, {}, *triangles};
    }
    if (name.starts_with(kPlumePrefix)) {
        std::optional<int> resolution = parseResolution(name.substr(std::string(kPlumePrefix).size()));
        if (!resolution) {
            throw Error("scene " + name + ": expected plume_<N> with N from 2 to 1290 voxels along each axis, e.g. "
                        "plume_64");
        }
        std::filesystem::path shipped = scenesDirectory / (std::string(kPlumeScene) + ".gltf");
        if (const std::string reason = notRegularFileReason(shipped); !reason.empty()) {
            throw Error("scene " + name + ": the plume goes into " + shipped.string() + ": " + reason);
        }
        return {name, shipped, 0, *resolution};
    }
    std::filesystem::path shipped = scenesDirectory / (name + ".gltf");
    if (const std::string reason = notRegularFileReason(shipped); reason != "no such file" && !reason.empty()) {
        throw Error("scene " + name + ": " + shipped.string() + ": " + reason);
    }
    if (!notRegularFileReason(shipped).empty()) {
        throw Error("unknown scene '" + name + "': not " + shipped.string() +
                    ", nor room_<N> (e.g. room_100k), nor plume_<N> (e.g. plume_64), nor a .gltf or .glb file");
    }
    return {name, shipped};
}

BenchMemoryEstimate estimateBenchMemory(const BenchSceneSource& source) {
    const uint64_t voxels = uint64_t(source.plumeResolution) * uint64_t(source.plumeResolution) *
                            uint64_t(source.plumeResolution);
    BenchMemoryEstimate estimate;
    estimate.hostBytes = source.roomTriangles * kHostBytesPerTriangle + voxels * kHostBytesPerVoxel;
    estimate.deviceBytes = source.roomTriangles * kDeviceBytesPerTriangle +
                           voxels * (kForwardDeviceBytesPerVoxel + kGradientDeviceBytesPerVoxel);
    estimate.deviceHeapBytes = std::max(estimate.deviceBytes, 2 * voxels * gpu::kFixedPointWordsPerSum * 8);
    return estimate;
}

std::optional<std::string> whyTooLarge(const BenchSceneSource& source, uint64_t availableHostBytes,
                                       uint64_t deviceHeapBytes, bool deviceIsHost) {
    const BenchMemoryEstimate estimate = estimateBenchMemory(source);
    const uint64_t host = estimate.hostBytes + (deviceIsHost ? estimate.deviceBytes : 0);
    const uint64_t device = estimate.deviceHeapBytes;
    auto gib = [](uint64_t bytes) { return formatText("%.1f GiB", double(bytes) / double(1ull << 30)); };
    if (host > availableHostBytes) {
        return "needs about " + gib(host) + " of host memory, " + gib(availableHostBytes) + " available";
    }
    if (device > deviceHeapBytes) {
        return "needs about " + gib(device) + " of device memory, the device has " + gib(deviceHeapBytes);
    }
    return std::nullopt;
}

LoadedScene loadBenchScene(const BenchSceneSource& source, const SceneFileAccess& access) {
    if (!source.file.empty()) {
        LoadedScene loaded = loadScene(source.file, access);
        if (source.plumeResolution > 0) {
            replaceGridsWithPlume(loaded.scene, source);
        }
        return loaded;
    }
    static std::atomic<int> counter{0};
    std::filesystem::path file = std::filesystem::temp_directory_path() /
                                 ("vkdr-bench-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + ".glb");
    std::error_code ignored;
    try {
        writeRoomScene({source.roomTriangles, file, kRoomFog});
        Scene scene = loadScene(file).scene;
        std::filesystem::remove(file, ignored);
        return {std::move(scene), {}, {}};
    } catch (...) {
        std::filesystem::remove(file, ignored);
        throw;
    }
}

}  // namespace vkdr
