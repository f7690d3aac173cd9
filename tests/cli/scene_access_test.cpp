// What the command line reads: a scene's external files only inside its own directory
// unless --allow-outside-files is given, and no input that is not a regular file (a
// directory or a FIFO fails at once with one `error:` line, exit code 2; nothing waits).
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

const fs::path kValidQuad = fs::path(VKDR_TEST_DATA_DIR) / "malformed" / "valid_quad.gltf";
const fs::path kValidTarget = fs::path(VKDR_TEST_DATA_DIR) / "malformed" / "valid_target.exr";
const std::string kFog = std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf";

// The quad's 60 bytes of positions and indices, as valid_quad.gltf has them in a data URI.
std::string quadBuffer() {
    const float positions[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::string bytes(60, '\0');
    std::memcpy(bytes.data(), positions, 48);
    std::memcpy(bytes.data() + 48, indices, 12);
    return bytes;
}

class SceneAccess : public ::testing::Test {
protected:
    void SetUp() override {
        scratch_ = fs::temp_directory_path() / ("vkdr-scene-access-" + std::to_string(getpid()));
        fs::remove_all(scratch_);
        fs::create_directories(scratch_ / "scene");
        fs::create_directories(scratch_ / "secret");
        fs::create_directories(scratch_ / "out");
        std::ofstream(scratch_ / "secret" / "geom.bin", std::ios::binary) << quadBuffer();
    }
    void TearDown() override { fs::remove_all(scratch_); }

    // valid_quad.gltf in scratch/scene, its buffer the file `uri` names.
    fs::path quadWithBufferUri(const std::string& uri) const {
        nlohmann::json document = nlohmann::json::parse(std::ifstream(kValidQuad));
        document["buffers"][0]["uri"] = uri;
        fs::path file = scratch_ / "scene" / "quad.gltf";
        std::ofstream(file) << document.dump();
        return file;
    }
    RunResult render(const fs::path& scene, const std::string& extra = "") const {
        return runCli("render " + scene.string() + " --width 8 --height 8 --spp 1 -o " +
                          (scratch_ / "out" / "x.exr").string() + " " + extra,
                      scratch_);
    }
    fs::path fifo(const std::string& name) const {
        fs::path file = scratch_ / name;
        EXPECT_EQ(::mkfifo(file.c_str(), 0600), 0);
        return file;
    }

    fs::path scratch_;
};

void expectOneError(const RunResult& r, const std::vector<std::string>& parts) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    ASSERT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line:\n" << r.err;
    for (const std::string& part : parts) EXPECT_NE(r.err.find(part), std::string::npos) << part << " in:\n" << r.err;
}

TEST_F(SceneAccess, ReadsFilesOutsideTheSceneDirectoryOnlyWhenAllowed) {
    fs::path scene = quadWithBufferUri("../secret/geom.bin");
    RunResult refused = render(scene);
    expectOneError(refused, {"quad.gltf", "buffers[0].uri", "'../secret/geom.bin'", "--allow-outside-files"});
    // The scratch directory's name may hold any digits; the rest must not give the size.
    std::string message = refused.err;
    for (size_t at; (at = message.find(scratch_.string())) != std::string::npos;) {
        message.erase(at, scratch_.string().size());
    }
    EXPECT_EQ(message.find("60"), std::string::npos) << "the message gives the file's size:\n" << refused.err;
    EXPECT_TRUE(fs::is_empty(scratch_ / "out"));
    EXPECT_EQ(render(scene, "--allow-outside-files").exitCode, 0);
}

TEST_F(SceneAccess, ReadsAbsolutePathsOnlyWhenAllowed) {
    fs::path scene = quadWithBufferUri((scratch_ / "secret" / "geom.bin").string());
    expectOneError(render(scene), {"quad.gltf", "buffers[0].uri", "absolute path"});
    RunResult allowed = render(scene, "--allow-outside-files");
    EXPECT_EQ(allowed.exitCode, 0) << allowed.err;
}

TEST_F(SceneAccess, RefusesABufferThatIsADirectoryOrAFifo) {
    fs::create_directory(scratch_ / "scene" / "folder.bin");
    expectOneError(render(quadWithBufferUri("folder.bin")), {"buffers[0].uri", "'folder.bin' is a directory"});
    EXPECT_EQ(::mkfifo((scratch_ / "scene" / "pipe.bin").c_str(), 0600), 0);
    expectOneError(render(quadWithBufferUri("pipe.bin")), {"buffers[0].uri", "'pipe.bin' is a FIFO"});
}

TEST_F(SceneAccess, RefusesASceneOrTargetThatIsAFifo) {
    expectOneError(render(fifo("scene.gltf")), {"scene.gltf", "FIFO"});
    fs::path target = fifo("target.exr");
    expectOneError(runCli("grad " + kFog + " --target " + target.string() + " --param media/fog/g --spp 1", scratch_),
                   {"target.exr", "FIFO"});
}

TEST_F(SceneAccess, RefusesAnExperimentFileThatIsADirectoryOrAFifo) {
    fs::create_directory(scratch_ / "folder.json");
    for (const fs::path& experiment : {scratch_ / "folder.json", fifo("pipe.json")}) {
        expectOneError(runCli("optimize --experiment " + experiment.string() + " --out " + (scratch_ / "out").string(),
                              scratch_),
                       {experiment.string(), experiment.filename() == "pipe.json" ? "FIFO" : "is a directory"});
    }
    EXPECT_TRUE(fs::is_empty(scratch_ / "out"));
}

// The checkpoint is read before any device work, of a run and of an experiment: the
// error is the run's first line.
TEST_F(SceneAccess, RefusesACheckpointThatIsADirectoryOrAFifo) {
    const std::string run = "optimize " + kFog + " --target " + kValidTarget.string() +
                            " --param media/fog/g --iters 2 --spp 1 --max-depth 1 --resume ";
    const std::string experiment =
        "optimize --experiment " + std::string(VKDR_TEST_SCENES_DIR) + "/experiments/cornell_absorption.json --resume ";
    fs::create_directories(scratch_ / "with_folder" / "checkpoint.json");
    fs::create_directories(scratch_ / "with_fifo");
    fifo("with_fifo/checkpoint.json");
    for (const std::string& optimize : {run, experiment}) {
        for (const auto& [directory, problem] :
             {std::pair{"with_folder", "is a directory"}, {"with_fifo", "is a FIFO"}}) {
            RunResult r = runCli(optimize + (scratch_ / directory).string(), scratch_);
            EXPECT_EQ(r.exitCode, 2) << r.err;
            std::string error = "error: " + (scratch_ / directory / "checkpoint.json").string() + ": " + problem;
            EXPECT_EQ(r.err.find(error), 0u) << optimize << "\n" << r.err;
            EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << "more than one error:\n" << r.err;
        }
    }
}

}  // namespace
}  // namespace vkdr::test
