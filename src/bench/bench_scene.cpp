#include "bench/bench_scene.h"

#include <unistd.h>

#include <atomic>
#include <charconv>
#include <optional>
#include <system_error>

#include "core/error.h"
#include "procedural/room_scene.h"
#include "scene/load_scene.h"

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

bool looksLikeFile(const std::string& name) {
    std::filesystem::path path(name);
    return path.has_parent_path() || path.extension() == ".gltf" || path.extension() == ".glb";
}

}  // namespace

std::vector<std::string> defaultBenchScenes() {
    return {"cornell_fog", "cornell_smoke", "room_10k", "room_100k", "room_1m", "room_10m"};
}

BenchSceneSource resolveBenchScene(const std::string& name, const std::filesystem::path& scenesDirectory) {
    if (looksLikeFile(name)) {
        if (!std::filesystem::is_regular_file(name)) {
            throw Error("scene " + name + ": no such file");
        }
        return {name, name, 0};
    }
    if (name.starts_with(kRoomPrefix)) {
        std::optional<uint64_t> triangles = parseCount(name.substr(std::string(kRoomPrefix).size()));
        if (!triangles || *triangles == 0 || *triangles > kMaxRoomTriangles) {
            throw Error("scene " + name + ": expected room_<N> with N from 1 to 2^30 triangles, e.g. room_100k");
        }
        return {name, {}, *triangles};
    }
    std::filesystem::path shipped = scenesDirectory / (name + ".gltf");
    if (!std::filesystem::is_regular_file(shipped)) {
        throw Error("unknown scene '" + name + "': not " + shipped.string() +
                    ", nor room_<N> (e.g. room_100k), nor a .gltf or .glb file");
    }
    return {name, shipped, 0};
}

std::optional<std::string> whyTooLarge(const BenchSceneSource& source, uint64_t availableHostBytes,
                                       uint64_t deviceHeapBytes, bool deviceIsHost) {
    const uint64_t host = source.roomTriangles * (kHostBytesPerTriangle + (deviceIsHost ? kDeviceBytesPerTriangle : 0));
    const uint64_t device = source.roomTriangles * kDeviceBytesPerTriangle;
    auto gib = [](uint64_t bytes) { return std::to_string((bytes + (1ull << 29)) >> 30) + " GiB"; };
    if (host > availableHostBytes) {
        return "needs about " + gib(host) + " of host memory, " + gib(availableHostBytes) + " available";
    }
    if (device > deviceHeapBytes) {
        return "needs about " + gib(device) + " of device memory, the device has " + gib(deviceHeapBytes);
    }
    return std::nullopt;
}

Scene loadBenchScene(const BenchSceneSource& source) {
    if (!source.file.empty()) {
        return loadScene(source.file).scene;
    }
    static std::atomic<int> counter{0};
    std::filesystem::path file = std::filesystem::temp_directory_path() /
                                 ("vkdr-bench-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + ".glb");
    std::error_code ignored;
    try {
        writeRoomScene({source.roomTriangles, file, kRoomFog});
        Scene scene = loadScene(file).scene;
        std::filesystem::remove(file, ignored);
        return scene;
    } catch (...) {
        std::filesystem::remove(file, ignored);
        throw;
    }
}

}  // namespace vkdr
