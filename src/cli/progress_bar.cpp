#include "cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vkdr {

constexpr int kBarWidth = 30;

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
    finish();
}

void ProgressBar::update(double fraction, const std::string& status) {
    if (!enabled_) {
        return;
    }
    fraction = std::clamp(fraction, 0.0, 1.0);
    int filled = int(fraction * kBarWidth + 0.5);
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string bar(filled, '#');
    bar.resize(kBarWidth, '.');
    char figures[32];
    std::snprintf(figures, sizeof figures, "%3d%% %6.1fs", int(fraction * 100.0 + 0.5), elapsed);
    std::string line = label_ + " [" + bar + "] " + figures + " " + status;
    if (line == drawn_) {
        return;
    }
    // Spaces cover what is left of a longer line drawn before.
    const size_t cover = drawn_.size() > line.size() ? drawn_.size() - line.size() : 0;
    drawn_ = std::move(line);
    std::fprintf(stderr, "\r%s%*s", drawn_.c_str(), int(cover), "");
    std::fflush(stderr);
}

void ProgressBar::finish() {
    if (enabled_ && !finished_) {
        std::fprintf(stderr, "\n");
        finished_ = true;
    }
}

}  // namespace vkdr
