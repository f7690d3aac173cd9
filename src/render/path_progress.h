#pragma once
#include <cstdint>
#include <functional>

namespace vkdr {

// Progress in [0, 1].
using ProgressCallback = std::function<void(double)>;

// The share done of a job of a known number of path traces, reported as paths end
// rather than only between passes: most jobs on a CPU device are one long pass. A
// render traces each sample once; a gradient evaluation also back-propagates it, and
// replays it where its radiance was not kept.
class PathProgress {
public:
    // While a Job lives, its progress is reported; a job with an empty callback reports
    // nothing. One job at a time.
    class Job {
    public:
        Job(PathProgress& progress, ProgressCallback report, uint64_t totalPaths);
        ~Job();
        Job(const Job&) = delete;
        Job& operator=(const Job&) = delete;

    private:
        PathProgress& progress_;
    };

    // `ended` of the current pass's paths have ended so far.
    void passUnderway(uint64_t ended) const;
    // The current pass, of `passPaths` paths, is over.
    void passEnded(uint64_t passPaths);

private:
    void report(uint64_t done) const;

    ProgressCallback report_;
    uint64_t total_ = 0;
    uint64_t done_ = 0;
};

}  // namespace vkdr
