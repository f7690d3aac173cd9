#pragma once
#include <chrono>
#include <string>

namespace vkdr {

// A one-line progress bar on stderr, drawn only when stderr is a terminal.
class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar();
    void update(double fraction, const std::string& status = "");
    void finish();

private:
    std::string label_;
    bool enabled_;
    bool finished_ = false;
    std::string drawn_;  // the line on screen: an update that would draw it again does not
    std::chrono::steady_clock::time_point start_;
};

}  // namespace vkdr
