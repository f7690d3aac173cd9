#include "render/path_progress.h"

#include <algorithm>
#include <utility>

namespace vkdr {

PathProgress::Job::Job(PathProgress& progress, ProgressCallback report, uint64_t totalPaths) : progress_(progress) {
    progress_.report_ = std::move(report);
    progress_.total_ = totalPaths;
    progress_.done_ = 0;
}

PathProgress::Job::~Job() {
    progress_.report_ = {};
}

void PathProgress::passUnderway(uint64_t ended) const {
    report(done_ + ended);
}

void PathProgress::passEnded(uint64_t passPaths) {
    done_ += passPaths;
    report(done_);
}

void PathProgress::report(uint64_t done) const {
    if (report_ && total_ > 0) {
        report_(std::min(1.0, double(done) / double(total_)));
    }
}

}  // namespace vkdr
