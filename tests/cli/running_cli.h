#pragma once
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "cli_run.h"

namespace vkdr::test {

// vkdiffrender started in the background, so that a test can send it a real signal
// once it has reached a given point (a file it writes, a line it prints).
class RunningCli {
public:
    RunningCli(const std::string& args, const std::filesystem::path& scratch, const std::string& environment = "")
        : scratch_(scratch) {
        // `exec` twice over: the signal must reach vkdiffrender, not a shell.
        std::string command = "exec env " + environment + " " + std::string(VKDR_CLI_PATH) + " " + args + " > " +
                              (scratch / "stdout").string() + " 2> " + (scratch / "stderr").string() + " < /dev/null";
        pid_ = fork();
        if (pid_ == 0) {
            execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
    }
    ~RunningCli() {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    RunningCli(const RunningCli&) = delete;
    RunningCli& operator=(const RunningCli&) = delete;

    // Polls until `ready` holds; false if the process ended first. The bound only keeps
    // a broken build from hanging the suite: no result depends on how long anything takes.
    bool waitUntil(const std::function<bool()>& ready) {
        auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
        while (std::chrono::steady_clock::now() < deadline) {
            if (ready()) return true;
            if (waitpid(pid_, &status_, WNOHANG) == pid_) {
                pid_ = -1;
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return false;
    }

    void signal(int number) { kill(pid_, number); }

    // Whether the process has installed a handler for `number` (Linux's /proc), so that
    // the signal is certain to be handled rather than to kill it.
    bool catches(int number) const {
        std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
        for (std::string line; std::getline(status, line);) {
            if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (number - 1)) & 1;
        }
        return false;
    }

    // Waits for the process to end; exitCode is -1 when a signal killed it.
    RunResult finish() {
        if (pid_ > 0) {
            waitpid(pid_, &status_, 0);
            pid_ = -1;
        }
        return {WIFEXITED(status_) ? WEXITSTATUS(status_) : -1, slurp(scratch_ / "stdout"),
                slurp(scratch_ / "stderr")};
    }

private:
    std::filesystem::path scratch_;
    pid_t pid_ = -1;
    int status_ = 0;
};

}  // namespace vkdr::test
