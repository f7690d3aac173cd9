// GLB chunks that tinygltf skips are warned about; a chunk running past the file is refused.
#include <cstring>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "expect_error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& file) {
    std::stringstream s;
    s << std::ifstream(file, std::ios::binary).rdbuf();
    return s.str();
}

void appendUint32(std::string& bytes, uint32_t value) { bytes.append(reinterpret_cast<const char*>(&value), 4); }

// A box GLB with `extra` appended after its chunks, and the header's length updated
// when `counted`.
fs::path boxGlbWith(const TemporaryDirectory& directory, const std::string& extra, bool counted = true) {
    GltfBuilder builder;
    builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}))}});
    fs::path file = builder.writeGlb(directory / "box.glb");
    std::string bytes = bytesOf(file) + extra;
    if (counted) {
        uint32_t length = uint32_t(bytes.size());
        std::memcpy(bytes.data() + 8, &length, 4);
    }
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
}

std::string chunk(const char type[4], uint32_t length) {
    std::string bytes;
    appendUint32(bytes, length);
    bytes.append(type, 4);
    return bytes + std::string(length, '\0');
}

bool warnsAbout(const LoadedScene& loaded, const std::vector<std::string>& parts) {
    for (const std::string& warning : loaded.warnings) {
        bool all = true;
        for (const std::string& part : parts) all = all && warning.find(part) != std::string::npos;
        if (all) return true;
    }
    return false;
}

TEST(GlbLayout, WarnsAboutChunksAfterTheFirstBinaryChunk) {
    TemporaryDirectory directory;
    fs::path file = boxGlbWith(directory, chunk("BIN\0", 16) + chunk("XTRA", 8));
    LoadedScene loaded = loadScene(file);
    EXPECT_EQ(loaded.scene.triangles.size(), 12u);
    EXPECT_TRUE(warnsAbout(loaded, {"box.glb", "GLB chunk 2 (BIN, 16 bytes) is ignored"}));
    EXPECT_TRUE(warnsAbout(loaded, {"box.glb", "GLB chunk 3 (XTRA, 8 bytes) is ignored"}));
}

TEST(GlbLayout, WarnsAboutBytesPastTheDeclaredLength) {
    TemporaryDirectory directory;
    LoadedScene loaded = loadScene(boxGlbWith(directory, std::string(8, '\0'), false));
    EXPECT_TRUE(warnsAbout(loaded, {"box.glb", "8 bytes after the length the GLB header declares"}));
}

TEST(GlbLayout, RefusesAChunkRunningPastTheEnd) {
    TemporaryDirectory directory;
    std::string truncated = chunk("XTRA", 8);
    truncated.resize(12);
    expectErrorMentioning([&] { loadScene(boxGlbWith(directory, truncated)); },
                          {"box.glb", "GLB chunk 2 runs past the end of the file"});
}

}  // namespace
}  // namespace vkdr::test
