#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace vkdr::test {

struct RunResult {
    int exitCode;  // -1 when the process did not exit normally (a crash)
    std::string out;
    std::string err;
};

inline std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs vkdiffrender with `args` (shell syntax) and `environment` (NAME=VALUE ...), its
// stdout and stderr captured in files in `scratch`.
inline RunResult runCli(const std::string& args, const std::filesystem::path& scratch,
                        const std::string& environment = "") {
    std::string command = environment + " " + std::string(VKDR_CLI_PATH) + " " + args + " > " +
                          (scratch / "stdout").string() + " 2> " + (scratch / "stderr").string() + " < /dev/null";
    int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(scratch / "stdout"), slurp(scratch / "stderr")};
}

// A command-line test with a scratch directory of its own, named after its suite, test
// and process (two test runs on one machine keep apart), made empty before the test and
// removed after it.
class CliScratchTest : public ::testing::Test {
protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("vkdr_" + std::string(info->test_suite_name()) + "_" + std::to_string(getpid())) / info->name();
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
        std::filesystem::remove(dir_.parent_path(), ignored);  // only once empty
    }

    RunResult run(const std::string& args) { return runCli(args, dir_); }
    static std::string fog() { return std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf"; }

    std::filesystem::path dir_;
};

}  // namespace vkdr::test
