// The malformed-input corpus (data/malformed, made by make_corpus.py): every file makes
// the command line fail with one `error:` line naming the file and the field at fault,
// exit code 2, and no output written.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(VKDR_TEST_DATA_DIR) / "malformed";

struct MalformedCase {
    std::string file;
    std::string command;              // "render" (a scene), "grad" (a target of the fog Cornell box) or
                                      // "experiment" (optimize --experiment)
    std::vector<std::string> expect;  // besides the file name, what the message must name
    std::string extra;                // further arguments
};

std::vector<MalformedCase> corpusCases() {
    std::ifstream in(kCorpus / "cases.json");
    std::vector<MalformedCase> cases;
    for (const nlohmann::json& entry : nlohmann::json::parse(in)) {
        cases.push_back({entry["file"], entry["command"], entry["expect"], entry["extra"]});
    }
    return cases;
}

class MalformedInput : public ::testing::TestWithParam<MalformedCase> {
protected:
    void SetUp() override {
        scratch_ = fs::temp_directory_path() / ("vkdr-malformed-" + std::to_string(getpid()));
        fs::remove_all(scratch_);
        fs::create_directories(scratch_ / "out");
    }
    void TearDown() override { fs::remove_all(scratch_); }

    // The command for `file`; render and optimize write into scratch/out, which must stay empty.
    std::string commandFor(const MalformedCase& c) const {
        std::string file = (kCorpus / c.file).string();
        std::string fog = std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf";
        std::string common = " --spp 1 --max-depth 1 " + c.extra;
        if (c.command == "render") {
            return "render " + file + " --width 8 --height 8 -o " + (scratch_ / "out" / "x.exr").string() + common;
        }
        if (c.command == "experiment") {
            return "optimize --experiment " + file + " --out " + (scratch_ / "out").string() + common;
        }
        return "grad " + fog + " --target " + file + " --param media/fog/g" + common;
    }

    fs::path scratch_;
};

TEST_P(MalformedInput, FailsWithOneMessageNamingTheFileAndField) {
    const MalformedCase& c = GetParam();
    RunResult r = runCli(commandFor(c), scratch_);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    ASSERT_EQ(r.err.rfind("error: ", 0), 0u) << "does not start with the error:\n" << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line:\n" << r.err;
    EXPECT_NE(r.err.find(c.file), std::string::npos) << "does not name the file:\n" << r.err;
    for (const std::string& part : c.expect) {
        EXPECT_NE(r.err.find(part), std::string::npos) << "does not name '" << part << "':\n" << r.err;
    }
    EXPECT_TRUE(fs::is_empty(scratch_ / "out")) << "output written";
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedInput, ::testing::ValuesIn(corpusCases()),
                         [](const ::testing::TestParamInfo<MalformedCase>& info) {
                             std::string name = info.param.file;
                             for (char& ch : name) {
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             }
                             return name;
                         });

// The corpus is only worth something if each file is one defect away from good input.
TEST(MalformedInputCorpus, TheFilesItIsMadeFromAreValid) {
    fs::path scratch = fs::temp_directory_path() / ("vkdr-malformed-valid-" + std::to_string(getpid()));
    fs::create_directories(scratch);
    for (const char* scene : {"valid_quad.gltf", "valid_quad.glb"}) {
        RunResult r = runCli("render " + (kCorpus / scene).string() + " --width 8 --height 8 --spp 1 -o " +
                                 (scratch / "x.exr").string(),
                             scratch);
        EXPECT_EQ(r.exitCode, 0) << scene << ":\n" << r.err;
    }
    RunResult r = runCli("grad " + std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf --target " +
                             (kCorpus / "valid_target.exr").string() + " --param media/fog/g --spp 1 --max-depth 1",
                         scratch);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    fs::remove_all(scratch);
}

}  // namespace
}  // namespace vkdr::test
