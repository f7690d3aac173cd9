#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace vkdr::test
