// What a scene may read besides itself (scene/scene_file_access.h): files in its own
// directory tree, unless allowed more; never anything but a regular file.
#include <fstream>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "core/error.h"
#include "expect_error.h"
#include "gltf_test_files.h"
#include "scene/load_scene.h"
#include "scene/write_scene.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

json readJson(const fs::path& file) { return json::parse(std::ifstream(file)); }

// A box scene, scene/box.gltf, whose buffer is the external file scene/box.bin.
struct ExternalBufferScene {
    ExternalBufferScene() {
        GltfBuilder builder;
        builder.addNode({{"mesh", builder.addMesh("box", box({0, 0, 0}, {1, 1, 1}))}});
        fs::path glb = builder.writeGlb(directory / "box.glb");
        fs::create_directories(directory / "scene");
        writeSceneWithParameters(glb, loadScene(glb).scene, gltf());
        fs::remove(glb);
    }
    fs::path gltf() const { return directory / "scene" / "box.gltf"; }
    fs::path buffer() const { return directory / "scene" / "box.bin"; }

    // The scene with buffers[0].uri set to `uri`.
    fs::path withBufferUri(const std::string& uri) const {
        json document = readJson(gltf());
        document["buffers"][0]["uri"] = uri;
        return writeText(directory / "scene" / "edited.gltf", document.dump());
    }
    // The buffer moved to `place` (relative to the temporary directory).
    fs::path moveBuffer(const std::string& place) const {
        fs::create_directories((directory / place).parent_path());
        fs::rename(buffer(), directory / place);
        return directory / place;
    }

    TemporaryDirectory directory;
};

void expectRefused(const fs::path& scene, const std::vector<std::string>& parts, SceneFileAccess access = {}) {
    expectErrorMentioning([&] { loadScene(scene, access); }, parts);
}

std::string errorOf(const fs::path& scene) {
    try {
        loadScene(scene);
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

TEST(SceneFileAccess, ReadsBuffersInItsOwnDirectoryTree) {
    ExternalBufferScene s;
    EXPECT_EQ(loadScene(s.gltf()).scene.triangles.size(), 12u);
    s.moveBuffer("scene/data/box.bin");
    EXPECT_EQ(loadScene(s.withBufferUri("data/../data/box.bin")).scene.triangles.size(), 12u);
    fs::create_symlink("data/box.bin", s.directory / "scene" / "link.bin");
    EXPECT_EQ(loadScene(s.withBufferUri("link.bin")).scene.triangles.size(), 12u);
}

TEST(SceneFileAccess, RefusesBuffersOutsideItsDirectoryWithoutSayingTheirSize) {
    ExternalBufferScene s;
    fs::path secret = s.moveBuffer("secret/geom.bin");
    std::string size = std::to_string(fs::file_size(secret));
    for (const char* uri : {"../secret/geom.bin", "..%2Fsecret%2Fgeom.bin", "%2e%2e/secret/geom.bin",
                                   "../../../../../../../../etc/passwd"}) {
        fs::path scene = s.withBufferUri(uri);
        expectRefused(scene, {"edited.gltf", "buffers[0].uri", std::string(uri), "outside the scene's directory",
                              "--allow-outside-files"});
        // The scratch directory's name may hold any digits; the rest must not give the size.
        std::string message = errorOf(scene);
        const std::string directory = s.directory.path().string();
        for (size_t at; (at = message.find(directory)) != std::string::npos;) message.erase(at, directory.size());
        EXPECT_EQ(message.find(size), std::string::npos) << errorOf(scene);
    }
    EXPECT_EQ(loadScene(s.withBufferUri("../secret/geom.bin"), {true}).scene.triangles.size(), 12u);
}

TEST(SceneFileAccess, RefusesSymbolicLinksThatLeadOutside) {
    ExternalBufferScene s;
    fs::path secret = s.moveBuffer("secret/geom.bin");
    fs::create_symlink(secret, s.directory / "scene" / "link.bin");
    fs::create_directory_symlink(secret.parent_path(), s.directory / "scene" / "linked");
    expectRefused(s.withBufferUri("link.bin"), {"buffers[0].uri", "'link.bin'", "symbolic link"});
    expectRefused(s.withBufferUri("linked/geom.bin"), {"buffers[0].uri", "symbolic link"});
    EXPECT_EQ(loadScene(s.withBufferUri("link.bin"), {true}).scene.triangles.size(), 12u);
}

TEST(SceneFileAccess, ReadsAbsolutePathsOnlyWhenAllowed) {
    ExternalBufferScene s;
    fs::path scene = s.withBufferUri(fs::absolute(s.buffer()).string());
    expectRefused(scene, {"buffers[0].uri", fs::absolute(s.buffer()).string(), "absolute path",
                          "--allow-outside-files"});
    EXPECT_EQ(loadScene(scene, {true}).scene.triangles.size(), 12u);
}

TEST(SceneFileAccess, RefusesUrisWithASchemeAndBadEscapes) {
    ExternalBufferScene s;
    std::string fileUri = "file://" + fs::absolute(s.buffer()).string();
    expectRefused(s.withBufferUri(fileUri), {"buffers[0].uri", fileUri, "file:"});
    expectRefused(s.withBufferUri(fileUri), {"buffers[0].uri", "file:"}, {true});
    expectRefused(s.withBufferUri("box%2.bin"), {"buffers[0].uri", "two hex digits, got '2.'"});
    expectRefused(s.withBufferUri("box%zz.bin"), {"buffers[0].uri", "two hex digits, got 'zz'"});
    expectRefused(s.withBufferUri("box.bin%00.txt"), {"buffers[0].uri", "'%00' would put a NUL byte in the file name"});
    expectRefused(s.withBufferUri(std::string("box.bin\0.txt", 12)), {"buffers[0].uri", "NUL character"});
}

// tinygltf reads data URIs of a few media types in base64 only, and would take any other
// for a file's name; a .gltf buffer without a uri would be read as a file of no name.
TEST(SceneFileAccess, RefusesDataUrisItCannotReadAndBuffersWithoutUri) {
    ExternalBufferScene s;
    json document = readJson(s.gltf());
    for (const std::string uri : {"data:;base64,AAAA", "data:application/octet-stream,AAAA",
                                  "data:text/html;base64,AAAA"}) {
        document["buffers"][0] = {{"uri", uri}, {"byteLength", 3}};
        expectRefused(writeText(s.directory / "scene" / "data.gltf", document.dump()),
                      {"buffers[0].uri", "a data URI is read in base64",
                       "this one starts '" + uri.substr(0, uri.find(',')) + "'"});
    }
    document = readJson(s.gltf());
    document["buffers"][0].erase("uri");
    expectRefused(writeText(s.directory / "scene" / "no_uri.gltf", document.dump()),
                  {"buffers[0].uri", "missing: a buffer of a .gltf file needs one"});
}

TEST(SceneFileAccess, RefusesWhatIsNotARegularFile) {
    ExternalBufferScene s;
    fs::create_directory(s.directory / "scene" / "folder.bin");
    expectRefused(s.withBufferUri("folder.bin"), {"buffers[0].uri", "'folder.bin'", "is a directory"});
    ASSERT_EQ(::mkfifo((s.directory / "scene" / "pipe.bin").c_str(), 0600), 0);
    expectRefused(s.withBufferUri("pipe.bin"), {"buffers[0].uri", "'pipe.bin'", "FIFO"});
    expectRefused(s.withBufferUri("absent.bin"), {"buffers[0].uri", "'absent.bin'", "names no file"});

    fs::create_directory(s.directory / "scene" / "folder.gltf");
    expectRefused(s.directory / "scene" / "folder.gltf", {"folder.gltf", "is a directory"});
    ASSERT_EQ(::mkfifo((s.directory / "scene" / "pipe.gltf").c_str(), 0600), 0);
    expectRefused(s.directory / "scene" / "pipe.gltf", {"pipe.gltf", "FIFO"});
}

TEST(SceneFileAccess, RefusesImagesOutsideItsDirectory) {
    ExternalBufferScene s;
    writeText(s.directory / "outside.bmp", "not read");
    json document = readJson(s.gltf());
    document["images"] = {{{"uri", "../outside.bmp"}}};
    document["textures"] = {{{"source", 0}}};
    fs::path scene = writeText(s.directory / "scene" / "textured.gltf", document.dump());
    expectRefused(scene, {"textured.gltf", "images[0].uri", "'../outside.bmp'", "outside"});
}

}  // namespace
}  // namespace vkdr::test
